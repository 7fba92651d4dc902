#include "rig_models/haldex_hydraulics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace shudder::rig_models {

namespace {

constexpr double kPaPerBar = 1e5;
constexpr double kMaxSubstep_s = 5e-4;  // backward Euler: 0.5 ms against the chamber's ≥ 50 ms time constants

void require_positive(double v, const char* what) {
  if (!std::isfinite(v) || !(v > 0))
    throw std::invalid_argument(std::string("Haldex hydraulics: ") + what + " must be a finite value > 0");
}

void require_non_negative(double v, const char* what) {
  if (!std::isfinite(v) || v < 0)
    throw std::invalid_argument(std::string("Haldex hydraulics: ") + what + " must be a finite value >= 0");
}

// The positive root s of a s² + b s − c = 0 (a > 0, b >= 0, c >= 0), in the form that keeps
// its precision when b² >> a c.
double positive_root(double a, double b, double c) {
  const double d = b + std::sqrt(b * b + 4.0 * a * c);
  return d > 0 ? 2.0 * c / d : 0.0;
}

}  // namespace

HaldexHydraulics::HaldexHydraulics(const HaldexHydraulicsParams& p, double pack_torque_per_newton_m) : p_(p) {
  require_positive(p.relief_pressure_bar, "relief_pressure_bar");
  require_positive(p.piston_area_cm2, "piston_area_cm2");
  require_positive(p.pump_displacement_cm3_per_rev, "pump_displacement_cm3_per_rev");
  require_positive(p.chamber_volume_cm3, "chamber_volume_cm3");
  require_positive(p.bulk_modulus_bar, "bulk_modulus_bar");
  require_positive(p.pack_stiffness_N_per_mm, "pack_stiffness_N_per_mm");
  require_non_negative(p.valve_area_mm2, "valve_area_mm2");
  require_positive(p.discharge_coefficient, "discharge_coefficient");
  require_non_negative(p.leak_cm3_s_per_bar, "leak_cm3_s_per_bar");
  require_positive(p.oil_density_kg_m3, "oil_density_kg_m3");
  require_non_negative(p.preload_torque_Nm, "preload_torque_Nm");
  require_positive(pack_torque_per_newton_m, "the pack's torque per newton (n mu r_eff)");
  area_m2_ = p.piston_area_cm2 * 1e-4;
  preload_N_ = p.preload_torque_Nm / pack_torque_per_newton_m;
  displacement_m3_per_rad_ = p.pump_displacement_cm3_per_rev * 1e-6 / (2.0 * std::numbers::pi);
  compliance_m3_per_Pa_ = p.chamber_volume_cm3 * 1e-6 / (p.bulk_modulus_bar * kPaPerBar) +
                          area_m2_ * area_m2_ / (p.pack_stiffness_N_per_mm * 1e3);
  leak_m3_s_per_Pa_ = p.leak_cm3_s_per_bar * 1e-6 / kPaPerBar;
  valve_k_ = p.discharge_coefficient * p.valve_area_mm2 * 1e-6 * std::sqrt(2.0 / p.oil_density_kg_m3);
}

double HaldexHydraulics::step_pressure_bar(double pressure_bar, double rotation_rad, double step_s, double opening,
                                           double setting_bar, double leak_scale) const {
  const double cap_Pa = std::clamp(setting_bar, 0.0, p_.relief_pressure_bar) * kPaPerBar;
  double p_Pa = std::clamp(pressure_bar * kPaPerBar, 0.0, cap_Pa);
  if (!(step_s > 0)) return p_Pa / kPaPerBar;
  const double flow_m3_s = displacement_m3_per_rad_ * std::abs(rotation_rad) / step_s;
  const double valve = valve_k_ * std::clamp(opening, 0.0, 1.0);
  const double leak = leak_m3_s_per_Pa_ * std::max(leak_scale, 0.0);
  const int n = static_cast<int>(std::ceil(step_s / kMaxSubstep_s - 1e-9));
  const double h = step_s / n;
  for (int k = 0; k < n; ++k) {
    // C (p1 − p0)/h = Q − valve √p1 − leak p1, a quadratic in s = √p1; the caps (relief valve
    // and setting) pass whatever would exceed them.
    const double a = compliance_m3_per_Pa_ / h + leak;
    const double s = positive_root(a, valve, compliance_m3_per_Pa_ / h * p_Pa + flow_m3_s);
    p_Pa = std::min(s * s, cap_Pa);
  }
  return p_Pa / kPaPerBar;
}

double HaldexHydraulics::steady_pressure_bar(double slip_rad_s, double opening, double leak_scale) const {
  const double flow_m3_s = displacement_m3_per_rad_ * std::abs(slip_rad_s);
  const double valve = valve_k_ * std::clamp(opening, 0.0, 1.0);
  const double leak = leak_m3_s_per_Pa_ * std::max(leak_scale, 0.0);
  if (valve == 0.0 && leak == 0.0) return flow_m3_s > 0 ? p_.relief_pressure_bar : 0.0;
  // G s² + valve s − Q = 0 with s = √p.
  const double s = leak > 0 ? positive_root(leak, valve, flow_m3_s) : flow_m3_s / valve;
  return std::min(s * s / kPaPerBar, p_.relief_pressure_bar);
}

double HaldexHydraulics::clamp_force_N(double pressure_bar) const {
  return preload_N_ + area_m2_ * 1e5 * std::max(pressure_bar, 0.0);
}

}  // namespace shudder::rig_models
