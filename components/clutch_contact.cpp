#include "components/clutch_contact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace shudder::components {

void ClutchContext::set_ring_temperatures(const Eigen::VectorXd& ring_temp_C) {
  static_valid_ = false;
  held_.ring_temp_C = ring_temp_C;
  frozen_valid_ = false;
  ramp_ = false;
  frozen_end_valid_ = false;
  cached_slip_ = -1.0;
}

void ClutchContext::set_ring_temperature_ramp(const Eigen::VectorXd& start_C, const Eigen::VectorXd& end_C, double t0_s,
                                              double t1_s) {
  if (!(t1_s > t0_s)) throw std::invalid_argument("clutch context: a temperature ramp needs t1 > t0");
  static_valid_ = false;
  // The new start is the old far end (the multi-rate runs' continuous hold): its friction is
  // already frozen, at the same load.
  if (ramp_ && frozen_end_valid_ && start_C.size() == ring_temp_end_C_.size() && start_C == ring_temp_end_C_) {
    std::swap(frozen_, frozen_end_);
    frozen_valid_ = true;
  } else {
    frozen_valid_ = false;
  }
  held_.ring_temp_C = start_C;
  ring_temp_end_C_ = end_C;
  ramp_t0_s_ = t0_s;
  ramp_t1_s_ = t1_s;
  ramp_ = end_C != start_C;
  frozen_end_valid_ = false;
  cached_slip_ = -1.0;
}

void ClutchContext::set_normal_force(PiecewiseLinear normal_force_N) {
  // The caches are keyed by the force they were built at: only the last query's is dropped.
  held_.normal_force_N = std::move(normal_force_N);
  static_valid_ = false;
  cached_slip_ = -1.0;
}

double ClutchContext::ramp_weight(double t_s) const {
  return ramp_ ? std::clamp((t_s - ramp_t0_s_) / (ramp_t1_s_ - ramp_t0_s_), 0.0, 1.0) : 0.0;
}

ClutchHeldInputs ClutchContact::start_inputs(PiecewiseLinear normal_force_N) const {
  return {Eigen::VectorXd::Constant(clutch_->thermal().radial_cells(), clutch_->params().start_temp_C),
          std::move(normal_force_N)};
}

void ClutchContact::update(ClutchContext& c, double abs_slip, double t, double force) const {
  if (c.frozen_valid_ && abs_slip == c.cached_slip_ && t == c.cached_t_ && force == c.cached_force_) return;
  const double load = clutch_->friction_load_N(force);
  // The law holds its values outside its data's loads: two loads on the same side beyond them
  // give the same friction, so a clamp force moving there (a coupling's pressure below the
  // data's 10 kN) needs no new freeze.
  const auto [load_lo, load_hi] = clutch_->fluid().friction->load_range_N();
  const auto held = [&](double l) { return std::clamp(l, load_lo, load_hi); };
  if (!c.frozen_valid_ || std::abs(held(load) - held(c.frozen_.load_N)) > 1e-4 * std::abs(held(load))) {
    c.frozen_ = clutch_->freeze(c.held_.ring_temp_C, force);
    c.frozen_valid_ = true;
    c.frozen_end_valid_ = false;
  }
  if (c.ramp_) {
    if (!c.frozen_end_valid_) {
      c.frozen_end_ = clutch_->freeze(c.ring_temp_end_C_, force);
      c.frozen_end_valid_ = true;
    }
    // Both ends in one pass: they share the speed-only work (v^0.1, the tanh of shared rates).
    clutch_->ring_torque_pair_Nm(c.frozen_, c.frozen_end_, abs_slip, force, c.ring_torque_, c.ring_torque_end_);
    const double s = c.ramp_weight(t);
    c.ring_torque_ += s * (c.ring_torque_end_ - c.ring_torque_);
  } else {
    clutch_->ring_torque_Nm(c.frozen_, abs_slip, force, c.ring_torque_);
  }
  c.cached_slip_ = abs_slip;
  c.cached_t_ = t;
  c.cached_force_ = force;
}

double ClutchContact::drag_torque_at_force_Nm(double force_N) const {
  return drag_.enabled ? drag_.equivalent_mu * force_N * drag_.radius_m : 0.0;
}

double ClutchContact::drag_torque_Nm(const ClutchContext& c, double t) const {
  return drag_torque_at_force_Nm(c.held_.normal_force_N(t));
}

double ClutchContact::kinetic_torque_Nm(ClutchContext& c, double abs_slip, double t) const {
  return kinetic_torque_at_force_Nm(c, abs_slip, t, c.held_.normal_force_N(t));
}

double ClutchContact::kinetic_torque_at_force_Nm(ClutchContext& c, double abs_slip, double t, double force) const {
  update(c, abs_slip, t, force);
  return clutch_->params().sliding_interfaces * c.ring_torque_.sum() + drag_torque_at_force_Nm(force);
}

double ClutchContact::static_capacity_Nm(const ClutchContext& c, double t, double stick_time) const {
  return static_capacity_at_force_Nm(c, t, stick_time, c.held_.normal_force_N(t));
}

double ClutchContact::static_capacity_at_force_Nm(const ClutchContext& c, double t, double stick_time,
                                                  double force) const {
  const auto& p = clutch_->params();
  const auto& th = clutch_->thermal();
  // mu_s per ring at the held temperatures (the ratio to mu_k at the law's lowest speed), on a
  // ramp the same linear blend of its two ends as the kinetic torque.
  const double load = clutch_->friction_load_N(force);
  const auto weighted_sum = [&](const Eigen::VectorXd& ring_temp_C) {
    double sum = 0.0;
    for (Eigen::Index i = 0; i < ring_temp_C.size(); ++i)
      sum += th.ring_radius_m()[i] * th.ring_area_m2()[i] *
             clutch_->fluid().mu_static(clutch_->friction_temp_C(ring_temp_C[i]), load);
    return sum;
  };
  if (!c.static_valid_ || load != c.static_load_N_) {
    c.static_sum_start_ = weighted_sum(c.held_.ring_temp_C);
    c.static_sum_end_ = c.ramp_ ? weighted_sum(c.ring_temp_end_C_) : 0.0;
    c.static_load_N_ = load;
    c.static_valid_ = true;
  }
  double sum = c.static_sum_start_;
  if (c.ramp_) sum += c.ramp_weight(t) * (c.static_sum_end_ - sum);
  double growth = 1.0;
  if (stick_.enabled) growth += stick_.max_increase * (1.0 - std::exp(-stick_time / stick_.time_constant_s));
  return p.sliding_interfaces * clutch_->pressure_Pa(force) * sum * growth + drag_torque_at_force_Nm(force);
}

double ClutchContact::kinetic_torque_slope_Nms(ClutchContext& c, double abs_slip, double t) const {
  return kinetic_torque_slope_at_force_Nms(c, abs_slip, t, c.held_.normal_force_N(t));
}

double ClutchContact::kinetic_torque_slope_at_force_Nms(ClutchContext& c, double abs_slip, double t,
                                                        double force) const {
  // Central difference at constant (held) temperature; the step is far below the speed scale
  // of the friction curves (mm/s) yet far above round-off.
  const double h = std::max(1e-6, 1e-4 * abs_slip);
  const double lo = std::max(abs_slip - h, 0.0);
  return (kinetic_torque_at_force_Nm(c, abs_slip + h, t, force) - kinetic_torque_at_force_Nm(c, lo, t, force)) /
         (abs_slip + h - lo);
}

void ClutchContact::channel_heat_W(ClutchContext& c, double abs_slip, double t, double* out) const {
  channel_heat_at_force_W(c, abs_slip, t, c.held_.normal_force_N(t), out);
}

void ClutchContact::channel_heat_at_force_W(ClutchContext& c, double abs_slip, double t, double force,
                                            double* out) const {
  update(c, abs_slip, t, force);
  for (Eigen::Index i = 0; i < c.ring_torque_.size(); ++i) out[i] = c.ring_torque_[i] * abs_slip;
}

}  // namespace shudder::components
