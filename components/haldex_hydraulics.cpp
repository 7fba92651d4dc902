#include "components/haldex_hydraulics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace shudder::components {

namespace {

constexpr double kPaPerBar = 1e5;

void require_positive(double v, const char* what) {
  if (!std::isfinite(v) || !(v > 0))
    throw std::invalid_argument(std::string("Haldex hydraulics: ") + what + " must be a finite value > 0");
}

void require_non_negative(double v, const char* what) {
  if (!std::isfinite(v) || v < 0)
    throw std::invalid_argument(std::string("Haldex hydraulics: ") + what + " must be a finite value >= 0");
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
  require_positive(p.valve_time_constant_ms, "valve_time_constant_ms");
  require_positive(pack_torque_per_newton_m, "the pack's torque per newton (n mu r_eff)");
  area_m2_ = p.piston_area_cm2 * 1e-4;
  preload_N_ = p.preload_torque_Nm / pack_torque_per_newton_m;
  displacement_m3_per_rad_ = p.pump_displacement_cm3_per_rev * 1e-6 / (2.0 * std::numbers::pi);
  compliance_m3_per_Pa_ = p.chamber_volume_cm3 * 1e-6 / (p.bulk_modulus_bar * kPaPerBar) +
                          area_m2_ * area_m2_ / (p.pack_stiffness_N_per_mm * 1e3);
  leak_m3_s_per_Pa_ = p.leak_cm3_s_per_bar * 1e-6 / kPaPerBar;
  valve_k_ = p.discharge_coefficient * p.valve_area_mm2 * 1e-6 * std::sqrt(2.0 / p.oil_density_kg_m3);
}

double HaldexHydraulics::pressure_rate_bar_s(double pressure_bar, double abs_slip_rad_s, double opening,
                                             double setting_bar, double leak_scale) const {
  const double cap_Pa = std::clamp(setting_bar, 0.0, p_.relief_pressure_bar) * kPaPerBar;
  const double p_Pa = pressure_bar * kPaPerBar;
  const double lam_Pa = kLaminarPressure_bar * kPaPerBar;
  const double valve = valve_k_ * std::clamp(opening, 0.0, 1.0);
  // Below p_lam the orifice is linear through zero, so a small overshoot below 0 flows back.
  const double valve_flow = p_Pa >= lam_Pa ? valve * std::sqrt(p_Pa) : valve * p_Pa / std::sqrt(lam_Pa);
  const double flow_in = displacement_m3_per_rad_ * std::abs(abs_slip_rad_s);
  double rate_Pa_s =
      (flow_in - valve_flow - leak_m3_s_per_Pa_ * std::max(leak_scale, 0.0) * p_Pa) / compliance_m3_per_Pa_;
  // The relief valve opens in proportion to the pressure above its setting (its pressure
  // override): Q_r = (C/τ_r)(p − p_cap)⁺. Continuous in p, unlike an ideal cap, whose switch
  // an explicit integrator can only resolve by ever shorter steps.
  rate_Pa_s -= std::max(p_Pa - cap_Pa, 0.0) / kReliefTime_s;
  return rate_Pa_s / kPaPerBar;
}

double HaldexHydraulics::steady_pressure_bar(double slip_rad_s, double opening, double leak_scale,
                                             double setting_bar) const {
  // The rate falls strictly with p (every outflow grows with it) and is >= 0 at p = 0: bisect
  // between 0 and a pressure where the relief valve alone passes the whole pump flow.
  const auto rate = [&](double p) { return pressure_rate_bar_s(p, slip_rad_s, opening, setting_bar, leak_scale); };
  if (rate(0.0) <= 0.0) return 0.0;
  const double cap_bar = std::clamp(setting_bar, 0.0, p_.relief_pressure_bar);
  double lo = 0.0,
         hi = cap_bar +
              displacement_m3_per_rad_ * std::abs(slip_rad_s) * kReliefTime_s / compliance_m3_per_Pa_ / kPaPerBar +
              1e-9;
  while (rate(hi) > 0.0) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) (rate(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

double HaldexHydraulics::clamp_force_N(double pressure_bar) const {
  return preload_N_ + area_m2_ * kPaPerBar * std::max(pressure_bar, 0.0);
}

double HaldexHydraulics::pressure_for_force_bar(double force_N) const {
  return std::max(force_N - preload_N_, 0.0) / (area_m2_ * kPaPerBar);
}

}  // namespace shudder::components
