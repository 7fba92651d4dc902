#include "components/engine.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace shudder::components {

Engine::Engine(const EngineParams& p) : p_(p) {
  if (p.full_load_torque_Nm.min_value() < 0) throw std::invalid_argument("engine: the full-load torque must be >= 0");
  if (!(p.stall_speed_rpm > 0) || !(p.idle_speed_rpm > p.stall_speed_rpm) || !(p.max_speed_rpm > p.idle_speed_rpm))
    throw std::invalid_argument("engine: speeds must satisfy 0 < stall < idle < max");
  if (!(p.idle_governor_gain_Nms_per_rad >= 0) || !(p.loss_torque_idle_Nm >= 0) || !(p.loss_torque_max_Nm >= 0))
    throw std::invalid_argument("engine: governor gain and loss torques must be >= 0");
}

double Engine::torque_Nm(double omega, double throttle) const {
  const double n = units::rad_s_to_rpm(omega);
  const double full = p_.full_load_torque_Nm(n);
  const double idle = units::rpm_to_rad_s(p_.idle_speed_rpm);
  const double u = std::clamp(throttle, 0.0, 1.0);
  const double comb = std::clamp(u * full + p_.idle_governor_gain_Nms_per_rad * std::max(idle - omega, 0.0), 0.0, full);
  const double loss =
      (p_.loss_torque_idle_Nm + (p_.loss_torque_max_Nm - p_.loss_torque_idle_Nm) * n / p_.max_speed_rpm) *
      std::tanh(omega / 10.0);
  return comb - loss;
}

double Engine::torque_speed_slope_Nms_per_rad(double omega, double throttle) const {
  constexpr double h = 1e-3;  // rad/s: far below the map's breakpoint spacing (40 rad/s)
  return (torque_Nm(omega + h, throttle) - torque_Nm(omega - h, throttle)) / (2 * h);
}

double Engine::stall_speed_rad_s() const { return units::rpm_to_rad_s(p_.stall_speed_rpm); }

}  // namespace shudder::components
