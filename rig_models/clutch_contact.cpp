#include "rig_models/clutch_contact.hpp"

#include <cmath>

namespace shudder::rig_models {

void ClutchContext::set_ring_temperatures(const Eigen::VectorXd& ring_temp_C) {
  held_.ring_temp_C = ring_temp_C;
  frozen_valid_ = false;
  cached_slip_ = -1.0;
}

void ClutchContext::set_normal_force(PiecewiseLinear normal_force_N) {
  held_.normal_force_N = std::move(normal_force_N);
  frozen_valid_ = false;
  cached_slip_ = -1.0;
}

ClutchHeldInputs ClutchContact::start_inputs(PiecewiseLinear normal_force_N) const {
  return {Eigen::VectorXd::Constant(clutch_->thermal().radial_cells(), clutch_->params().start_temp_C),
          std::move(normal_force_N)};
}

void ClutchContact::update(ClutchContext& c, double abs_slip, double t) const {
  if (c.frozen_valid_ && abs_slip == c.cached_slip_ && t == c.cached_t_) return;
  const double force = c.held_.normal_force_N(t);
  const double load = clutch_->friction_load_N(force);
  if (!c.frozen_valid_ || std::abs(load - c.frozen_.load_N) > 1e-4 * std::abs(load)) {
    c.frozen_ = clutch_->freeze(c.held_.ring_temp_C, force);
    c.frozen_valid_ = true;
  }
  clutch_->ring_torque_Nm(c.frozen_, abs_slip, force, c.ring_torque_);
  c.cached_slip_ = abs_slip;
  c.cached_t_ = t;
}

double ClutchContact::drag_torque_Nm(const ClutchContext& c, double t) const {
  return drag_.enabled ? drag_.equivalent_mu * c.held_.normal_force_N(t) * drag_.radius_m : 0.0;
}

double ClutchContact::kinetic_torque_Nm(ClutchContext& c, double abs_slip, double t) const {
  update(c, abs_slip, t);
  return clutch_->params().sliding_interfaces * c.ring_torque_.sum() + drag_torque_Nm(c, t);
}

double ClutchContact::static_capacity_Nm(const ClutchContext& c, double t, double stick_time) const {
  const double force = c.held_.normal_force_N(t);
  const auto& p = clutch_->params();
  const auto& th = clutch_->thermal();
  const Eigen::VectorXd& ring_temp_C = c.held_.ring_temp_C;
  // mu_s per ring at the held temperatures (the ratio to mu_k at the law's lowest speed).
  const double load = clutch_->friction_load_N(force);
  double sum = 0.0;
  for (Eigen::Index i = 0; i < ring_temp_C.size(); ++i)
    sum += th.ring_radius_m()[i] * th.ring_area_m2()[i] *
           clutch_->fluid().mu_static(clutch_->friction_temp_C(ring_temp_C[i]), load);
  double growth = 1.0;
  if (stick_.enabled) growth += stick_.max_increase * (1.0 - std::exp(-stick_time / stick_.time_constant_s));
  return p.sliding_interfaces * clutch_->pressure_Pa(force) * sum * growth + drag_torque_Nm(c, t);
}

double ClutchContact::kinetic_torque_slope_Nms(ClutchContext& c, double abs_slip, double t) const {
  // Central difference at constant (held) temperature; the step is far below the speed scale
  // of the friction curves (mm/s) yet far above round-off.
  const double h = std::max(1e-6, 1e-4 * abs_slip);
  const double lo = std::max(abs_slip - h, 0.0);
  return (kinetic_torque_Nm(c, abs_slip + h, t) - kinetic_torque_Nm(c, lo, t)) / (abs_slip + h - lo);
}

void ClutchContact::channel_heat_W(ClutchContext& c, double abs_slip, double t, double* out) const {
  update(c, abs_slip, t);
  for (Eigen::Index i = 0; i < c.ring_torque_.size(); ++i) out[i] = c.ring_torque_[i] * abs_slip;
}

}  // namespace shudder::rig_models
