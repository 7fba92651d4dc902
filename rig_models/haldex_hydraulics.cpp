#include "rig_models/haldex_hydraulics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace shudder::rig_models {

namespace {

void require_positive(double v, const char* what) {
  if (!std::isfinite(v) || !(v > 0))
    throw std::invalid_argument(std::string("Haldex hydraulics: ") + what + " must be a finite value > 0");
}

}  // namespace

HaldexHydraulics::HaldexHydraulics(const HaldexHydraulicsParams& p, double pack_torque_per_newton_m) : p_(p) {
  require_positive(p.relief_pressure_bar, "relief_pressure_bar");
  require_positive(p.full_pressure_rotation_rad, "full_pressure_rotation_rad");
  require_positive(p.leak_time_constant_s, "leak_time_constant_s");
  require_positive(p.torque_per_bar_Nm, "torque_per_bar_Nm");
  require_positive(pack_torque_per_newton_m, "the pack's torque per newton (n mu r_eff)");
  if (!std::isfinite(p.preload_torque_Nm) || p.preload_torque_Nm < 0)
    throw std::invalid_argument("Haldex hydraulics: preload_torque_Nm must be a finite value >= 0");
  area_m2_ = p.torque_per_bar_Nm / (pack_torque_per_newton_m * 1e5);
  preload_N_ = p.preload_torque_Nm / pack_torque_per_newton_m;
}

double HaldexHydraulics::step_pressure_bar(double pressure_bar, double rotation_rad, double step_s,
                                           double valve_bar) const {
  const double tau = p_.leak_time_constant_s;
  const double rate_bar_per_rad = p_.relief_pressure_bar / p_.full_pressure_rotation_rad;
  const double steady_bar = step_s > 0 ? rate_bar_per_rad * std::abs(rotation_rad) / step_s * tau : 0.0;
  // p e^(−h/τ) + p_ss (1 − e^(−h/τ)), with expm1 so that a long τ keeps its precision.
  const double decay = std::expm1(-std::max(step_s, 0.0) / tau);
  const double p = pressure_bar * (1.0 + decay) - steady_bar * decay;
  const double limit = std::clamp(valve_bar, 0.0, p_.relief_pressure_bar);
  return std::clamp(p, 0.0, limit);
}

double HaldexHydraulics::clamp_force_N(double pressure_bar) const {
  return preload_N_ + area_m2_ * 1e5 * std::max(pressure_bar, 0.0);
}

}  // namespace shudder::rig_models
