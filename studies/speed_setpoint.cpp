#include "studies/speed_setpoint.hpp"

#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace shudder::studies {

std::vector<double> estimate_speed_setpoint(const std::vector<double>& t, const std::vector<double>& w_rpm,
                                            const std::vector<double>& torque_Nm, const rig_models::RigParams& rig) {
  const std::size_t n = t.size();
  if (w_rpm.size() != n || torque_Nm.size() != n)
    throw std::invalid_argument("estimate_speed_setpoint: time, speed and torque differ in length");
  for (std::size_t k = 1; k < n; ++k)
    if (!(t[k] > t[k - 1])) throw std::invalid_argument("estimate_speed_setpoint: time must increase strictly");
  if (n < 2) return w_rpm;

  const rig_models::SpeedLoopGains g = rig_models::speed_loop_gains(rig);
  const double tau_s = g.kp_Nms_per_rad / g.ki_Nm_per_rad;
  const double j = rig.drive_inertia_kg_m2;
  const auto w = [&](std::size_t k) { return units::rpm_to_rad_s(w_rpm[k]); };
  // Input of the derivative-free filter τ v' + v = q (the motor's torque less its ripple).

  std::vector<double> setpoint(n);
  // The ripple's phase follows the set point's angle, integrated as the set point is recovered:
  // sample k takes the angle predicted from sample k−1 (error ½ Δn h, ~1e-2 rad of ripple phase
  // at 1 kHz), then the trapezoid with the recovered value.
  double rev = 0.0, ripple_prev_Nm = motor_ripple_at_Nm(rig.motor_ripple, 0.0);
  const auto q = [&](std::size_t k, double ripple_Nm) { return torque_Nm[k] - ripple_Nm - j / tau_s * w(k); };
  double v = rig.start_at_rest ? -j / tau_s * w(0) : q(0, ripple_prev_Nm);  // y = 0 at rest, y = u steady
  for (std::size_t k = 0; k < n; ++k) {
    double ripple_Nm = ripple_prev_Nm;
    if (k > 0) {
      const double h = t[k] - t[k - 1];
      ripple_Nm = motor_ripple_at_Nm(rig.motor_ripple, rev + setpoint[k - 1] / 60.0 * h);
      const double q0 = q(k - 1, ripple_prev_Nm), q1 = q(k, ripple_Nm);
      const double slope = (q1 - q0) / h;
      // Exact for q linear over the step: particular solution q(t) − slope τ.
      v = q1 - slope * tau_s + (v - q0 + slope * tau_s) * std::exp(-h / tau_s);
    }
    const std::size_t a = k == 0 ? 0 : k - 1, b = k + 1 == n ? k : k + 1;
    const double dw_dt = (w(b) - w(a)) / (t[b] - t[a]);
    const double y = v + j / tau_s * w(k);
    const double e_rad_s = (j * dw_dt + torque_Nm[k] - ripple_Nm - y) / g.kp_Nms_per_rad;
    setpoint[k] = w_rpm[k] + units::rad_s_to_rpm(e_rad_s);
    if (k > 0) rev += 0.5 * (setpoint[k - 1] + setpoint[k]) / 60.0 * (t[k] - t[k - 1]);
    ripple_prev_Nm = ripple_Nm;
  }
  return setpoint;
}

}  // namespace shudder::studies
