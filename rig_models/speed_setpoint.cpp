#include "rig_models/speed_setpoint.hpp"

#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace shudder::rig_models {

std::vector<double> estimate_speed_setpoint(const std::vector<double>& t,
                                            const std::vector<double>& w_rpm,
                                            const std::vector<double>& torque_Nm, const RigParams& rig) {
  const std::size_t n = t.size();
  if (w_rpm.size() != n || torque_Nm.size() != n)
    throw std::invalid_argument("estimate_speed_setpoint: time, speed and torque differ in length");
  for (std::size_t k = 1; k < n; ++k)
    if (!(t[k] > t[k - 1]))
      throw std::invalid_argument("estimate_speed_setpoint: time must increase strictly");
  if (n < 2) return w_rpm;

  const SpeedLoopGains g = speed_loop_gains(rig);
  const double tau_s = g.kp_Nms_per_rad / g.ki_Nm_per_rad;
  const double j = rig.drive_inertia_kg_m2;
  const auto w = [&](std::size_t k) { return units::rpm_to_rad_s(w_rpm[k]); };
  // Input of the derivative-free filter τ v' + v = q.
  const auto q = [&](std::size_t k) { return torque_Nm[k] - j / tau_s * w(k); };

  std::vector<double> setpoint(n);
  double v = rig.start_at_rest ? -j / tau_s * w(0) : q(0);  // y = 0 at rest, y = u (= T) steady
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) {
      const double h = t[k] - t[k - 1];
      const double slope = (q(k) - q(k - 1)) / h;
      // Exact for q linear over the step: particular solution q(t) − slope τ.
      v = q(k) - slope * tau_s + (v - q(k - 1) + slope * tau_s) * std::exp(-h / tau_s);
    }
    const std::size_t a = k == 0 ? 0 : k - 1, b = k + 1 == n ? k : k + 1;
    const double dw_dt = (w(b) - w(a)) / (t[b] - t[a]);
    const double y = v + j / tau_s * w(k);
    const double e_rad_s = (j * dw_dt + torque_Nm[k] - y) / g.kp_Nms_per_rad;
    setpoint[k] = w_rpm[k] + units::rad_s_to_rpm(e_rad_s);
  }
  return setpoint;
}

}  // namespace shudder::rig_models
