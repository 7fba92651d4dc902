#include "components/engine_pulsation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::components {

EnginePulsationLaw::EnginePulsationLaw(const EnginePulsation& p, double stall_rad_s, double idle_rad_s)
    : p_(p), stall_rad_s_(stall_rad_s), idle_rad_s_(idle_rad_s) {
  if (!std::isfinite(p_.amplitude_Nm) || p_.amplitude_Nm < 0)
    throw std::invalid_argument("engine firing pulsation amplitude must be a finite value >= 0 N m");
  if (p_.cylinders < 1 || p_.cylinders > 16) throw std::invalid_argument("engine cylinders must be 1 to 16");
  if (!(stall_rad_s_ > 0) || !(idle_rad_s_ > stall_rad_s_) || !std::isfinite(idle_rad_s_))
    throw std::invalid_argument("engine firing pulsation needs 0 < stall speed < idle speed");
}

double EnginePulsationLaw::torque_Nm(double theta, double omega) const {
  const double x = std::clamp((omega - stall_rad_s_) / (idle_rad_s_ - stall_rad_s_), 0.0, 1.0);
  const double firing = x * x * (3.0 - 2.0 * x);
  return p_.amplitude_Nm * firing * std::sin(0.5 * p_.cylinders * theta);
}

dynamics::ForceLaw::Output EnginePulsationLaw::evaluate(double omega, double, const double* z, double* dzdt) const {
  const double t = torque_Nm(z[0], omega);
  dzdt[0] = omega;
  dzdt[1] = t * omega;
  // The element acts −T on its node a (network.hpp), so T = −T_p drives the engine by +T_p.
  return {-t, 0.0};
}

}  // namespace shudder::components
