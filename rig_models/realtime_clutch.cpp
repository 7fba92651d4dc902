#include "rig_models/realtime_clutch.hpp"

#include <cmath>
#include <stdexcept>

namespace shudder::rig_models {

long steps_per_thermal_step(const RealtimeSettings& s) {
  if (!(s.step_s > 0.0) || !std::isfinite(s.step_s))
    throw std::invalid_argument("fixed step must be a finite number > 0 s");
  if (!(s.thermal_step_s >= s.step_s) || !std::isfinite(s.thermal_step_s))
    throw std::invalid_argument("thermal step must be finite and >= the fixed step");
  const double ratio = s.thermal_step_s / s.step_s;
  const double n = std::round(ratio);
  if (std::abs(ratio - n) > 1e-9 * n)
    throw std::invalid_argument("the thermal step (thermal_step_s) must be a whole multiple of the fixed step");
  return static_cast<long>(n);
}

RealtimeClutch::RealtimeClutch(const clutch::WetClutch& clutch, const components::BearingDrag& drag,
                               const RealtimeSettings& settings, double force_N)
    : clutch_(clutch),
      drag_(drag),
      cfg_(settings),
      steps_per_window_(steps_per_thermal_step(settings)),
      // The worker looks for the posted window four times per window (rig_models/thermal_task.hpp).
      task_(clutch, force_N, 0.25 * settings.thermal_step_s),
      ring_torque_(Eigen::VectorXd::Zero(clutch.thermal().radial_cells())),
      mu_(Eigen::VectorXd::Zero(clutch.thermal().radial_cells())),
      window_heat_J_(Eigen::VectorXd::Zero(clutch.thermal().radial_cells())) {}

double RealtimeClutch::kinetic_torque_Nm(double abs_slip, double force_N) {
  const ThermalOutputs& th = task_.latest();
  const double load = clutch_.friction_load_N(force_N);
  if (std::abs(load - th.frozen.load_N) <= 1e-4 * std::abs(load)) {
    clutch_.ring_torque_Nm(th.frozen, abs_slip, force_N, ring_torque_);
  } else if (abs_slip > 0.0) {
    // Direct evaluation: heat / |Δω| is the ring torque (viscous shear included).
    clutch_.ring_heat_W(abs_slip, force_N, th.ring_temp_C, ring_torque_);
    ring_torque_ /= abs_slip;
  } else {  // at rest the viscous shear is zero: friction only
    clutch_.ring_mu(0.0, force_N, th.ring_temp_C, mu_);
    const auto& model = clutch_.thermal();
    ring_torque_ =
        mu_.cwiseProduct(model.ring_radius_m()).cwiseProduct(model.ring_area_m2()) * clutch_.pressure_Pa(force_N);
  }
  const double drag_Nm = drag_.enabled ? drag_.equivalent_mu * force_N * drag_.radius_m : 0.0;
  return clutch_.params().sliding_interfaces * ring_torque_.sum() + drag_Nm;
}

void RealtimeClutch::end_step(const Eigen::VectorXd& ring_heat_J, double slip_angle_rad, double t_end_s, double force_N,
                              double fraction) {
  window_heat_J_ += ring_heat_J;
  window_angle_rad_ += slip_angle_rad;
  steps_in_window_ += fraction;
  // With whole steps the count is an exact integer and this is `count < steps_per_window_`.
  if (steps_in_window_ < static_cast<double>(steps_per_window_) - kWindowSlack) return;
  // The window is complete: latch the previous window's result, hand this one over.
  task_.collect();
  const double dt = t_end_s - window_start_s_;
  task_.post(window_heat_J_, dt, t_end_s, window_angle_rad_ / dt, force_N);
  window_heat_J_.setZero();
  window_angle_rad_ = 0.0;
  window_start_s_ = t_end_s;
  steps_in_window_ = 0.0;
}

void RealtimeClutch::reset(double force_N) {
  task_.reset(force_N);
  window_heat_J_.setZero();
  window_angle_rad_ = 0.0;
  window_start_s_ = 0.0;
  steps_in_window_ = 0.0;
}

}  // namespace shudder::rig_models
