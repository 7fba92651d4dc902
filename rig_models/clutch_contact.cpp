#include "rig_models/clutch_contact.hpp"

#include <cmath>

namespace shudder::rig_models {

ClutchContactLaw::ClutchContactLaw(const clutch::WetClutch& clutch, PiecewiseLinear normal_force_N,
                                   BearingDrag drag, StickTimeFriction stick_time)
    : clutch_(clutch), force_N_(std::move(normal_force_N)), drag_(drag), stick_(stick_time) {
  set_ring_temperatures(Eigen::VectorXd::Constant(clutch_.thermal().radial_cells(),
                                                  clutch_.params().start_temp_C));
}

void ClutchContactLaw::set_ring_temperatures(const Eigen::VectorXd& ring_temp_C) {
  ring_temp_C_ = ring_temp_C;
  frozen_valid_ = false;
  cached_slip_ = -1.0;
}

void ClutchContactLaw::set_normal_force(PiecewiseLinear normal_force_N) {
  force_N_ = std::move(normal_force_N);
  frozen_valid_ = false;
  cached_slip_ = -1.0;
}

void ClutchContactLaw::update(double abs_slip, double t) const {
  if (frozen_valid_ && abs_slip == cached_slip_ && t == cached_t_) return;
  const double force = force_N_(t);
  const double load = clutch_.friction_load_N(force);
  if (!frozen_valid_ || std::abs(load - frozen_.load_N) > 1e-4 * std::abs(load)) {
    frozen_ = clutch_.freeze(ring_temp_C_, force);
    frozen_valid_ = true;
  }
  clutch_.ring_torque_Nm(frozen_, abs_slip, force, ring_torque_);
  cached_slip_ = abs_slip;
  cached_t_ = t;
}

double ClutchContactLaw::drag_torque_Nm(double t) const {
  return drag_.enabled ? drag_.equivalent_mu * force_N_(t) * drag_.radius_m : 0.0;
}

double ClutchContactLaw::kinetic_torque_Nm(double abs_slip, double t) const {
  update(abs_slip, t);
  return clutch_.params().sliding_interfaces * ring_torque_.sum() + drag_torque_Nm(t);
}

double ClutchContactLaw::static_capacity_Nm(double t, double stick_time) const {
  const double force = force_N_(t);
  const auto& p = clutch_.params();
  const auto& th = clutch_.thermal();
  // mu_s per ring at the held temperatures (the ratio to mu_k at the law's lowest speed).
  const double load = p.load_dependent_friction ? force : p.reference_load_N;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < ring_temp_C_.size(); ++i) {
    const double temp = p.temperature_dependent_friction ? ring_temp_C_[i] : p.start_temp_C;
    sum += th.ring_radius_m()[i] * th.ring_area_m2()[i] * clutch_.fluid().mu_static(temp, load);
  }
  double growth = 1.0;
  if (stick_.enabled) growth += stick_.max_increase * (1.0 - std::exp(-stick_time / stick_.time_constant_s));
  return p.sliding_interfaces * clutch_.pressure_Pa(force) * sum * growth + drag_torque_Nm(t);
}

double ClutchContactLaw::kinetic_torque_slope_Nms(double abs_slip, double t) const {
  // Central difference at constant (held) temperature; the step is far below the speed scale
  // of the friction curves (mm/s) yet far above round-off.
  const double h = std::max(1e-6, 1e-4 * abs_slip);
  const double lo = std::max(abs_slip - h, 0.0);
  return (kinetic_torque_Nm(abs_slip + h, t) - kinetic_torque_Nm(lo, t)) / (abs_slip + h - lo);
}

void ClutchContactLaw::channel_heat_W(double abs_slip, double t, double* out) const {
  update(abs_slip, t);
  for (Eigen::Index i = 0; i < ring_torque_.size(); ++i) out[i] = ring_torque_[i] * abs_slip;
}

}  // namespace shudder::rig_models
