// The first-generation Haldex hydraulics (components/haldex_hydraulics) against closed forms of
//   C dp/dt = D|Δω| − Q_v(p, u) − G p,   0 <= p <= min(p_relief, p_set),   C = V/β + A²/k,
//   Q_v = C_d u a √(2p/ρ) above p_lam = 0.01 bar, linear through zero below it:
//   * valve shut, no leakage: dp/dt = D|Δω|/C, so p = D φ / C after a relative rotation φ, and
//     the defaults reach the relief after a quarter turn of the WHEEL (2.6 × π/2 at the coupling);
//   * constant |Δω| with the valve open by u: the orifice equation's static pressure
//     p = ρ/2 (D|Δω| / (C_d u a))² is where the rate vanishes and where the pressure settles;
//     with leakage the root of G p + C_d u a √(2p/ρ) = D|Δω|;
//   * no rotation, valve shut: p0 e^(−t G/C) (the compliance time constant), and twice as fast
//     with half the viscosity;
//   * the orifice's two regimes meet continuously at p_lam;
//   * the relief valve (and a pressure setting) pass the surplus, Q_r = (C/τ_r)(p − p_cap)⁺:
//     the pressure settles where D|Δω| = G p + (C/τ_r)(p − p_cap), just above the cap;
//     F = A p (Gen I: no preload).
// Every expected value is computed here from the parameters, not from the class's getters. The
// pressure histories are integrated here by classical RK4 at 0.2 ms, far below the smallest time
// constant met (≈ 2 ms at p_lam with the valve open), so its error (≈ (h/τ)⁴) is below 1e-6.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "components/haldex_hydraulics.hpp"

namespace shudder::components {
namespace {

constexpr double kPackNmPerN = 16 * 0.12 * 0.04725;  // n μ r_eff of the 16-interface LSC pack

double displacement_m3_per_rad(const HaldexHydraulicsParams& p) {
  return p.pump_displacement_cm3_per_rev * 1e-6 / (2 * std::numbers::pi);
}
double compliance_m3_per_Pa(const HaldexHydraulicsParams& p) {
  const double area = p.piston_area_cm2 * 1e-4;
  return p.chamber_volume_cm3 * 1e-6 / (p.bulk_modulus_bar * 1e5) + area * area / (p.pack_stiffness_N_per_mm * 1e3);
}

// p(t) at constant slip, opening, setting and leakage scale, by RK4 at step h.
double integrate_bar(const HaldexHydraulics& h, double p0_bar, double slip_rad_s, double opening, double setting_bar,
                     double leak_scale, double duration_s, double step_s = 2e-4) {
  const auto f = [&](double p) { return h.pressure_rate_bar_s(p, slip_rad_s, opening, setting_bar, leak_scale); };
  double p = p0_bar;
  const long n = std::lround(duration_s / step_s);
  for (long k = 0; k < n; ++k) {
    const double k1 = f(p), k2 = f(p + 0.5 * step_s * k1), k3 = f(p + 0.5 * step_s * k2), k4 = f(p + step_s * k3);
    p += step_s / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return p;
}

TEST(HaldexHydraulics, ShutValveBuildsPumpVolumeOverComplianceAndFullPressureAfterAQuarterWheelTurn) {
  HaldexHydraulicsParams p;
  p.leak_cm3_s_per_bar = 0;
  const HaldexHydraulics h(p, kPackNmPerN);
  const double slip_rad_s = 3.0;
  const double expected_bar_s = displacement_m3_per_rad(p) * slip_rad_s / compliance_m3_per_Pa(p) / 1e5;
  // The rate is the pump's flow over the compliance whatever the pressure below the cap.
  for (double pressure : {0.0, 1.0, 17.0})
    EXPECT_NEAR(h.pressure_rate_bar_s(pressure, slip_rad_s, 0.0, 1e9), expected_bar_s, 1e-12 * expected_bar_s);
  EXPECT_NEAR(integrate_bar(h, 0.0, slip_rad_s, 0.0, 1e9, 1.0, 0.1), expected_bar_s * 0.1, 1e-9 * expected_bar_s);
  // Twice the speed difference, twice the flow; the pump works in either direction of slip.
  EXPECT_NEAR(h.pressure_rate_bar_s(1.0, 2 * slip_rad_s, 0.0, 1e9), 2 * expected_bar_s, 1e-12 * expected_bar_s);
  EXPECT_NEAR(h.pressure_rate_bar_s(1.0, -slip_rad_s, 0.0, 1e9), expected_bar_s, 1e-12 * expected_bar_s);
  // Public: full engagement after a quarter turn of the wheel; the coupling turns i_r = 2.6 times
  // the rear wheel. The defaults were set for it: within 1 % (0.3 % by the parameters' rounding).
  const double quarter_wheel_turn_rad = 2.6 * std::numbers::pi / 2;
  const double p_quarter_bar = displacement_m3_per_rad(p) * quarter_wheel_turn_rad / compliance_m3_per_Pa(p) / 1e5;
  EXPECT_NEAR(p_quarter_bar / p.relief_pressure_bar, 1.0, 0.01);
  // The relief valve passes the rest: two quarter turns in 0.1 s end at the relief pressure
  // plus its override Q τ_r / C (no leakage here), 0.4 % of it.
  const double q_rate_bar_s =
      displacement_m3_per_rad(p) * (2 * quarter_wheel_turn_rad / 0.1) / compliance_m3_per_Pa(p) / 1e5;
  EXPECT_NEAR(integrate_bar(h, 0.0, 2 * quarter_wheel_turn_rad / 0.1, 0.0, 1e9, 1.0, 0.1),
              p.relief_pressure_bar + q_rate_bar_s * HaldexHydraulics::kReliefTime_s, 1e-6);
}

TEST(HaldexHydraulics, ConstantSlipSettlesAtTheOrificeEquationsPressure) {
  HaldexHydraulicsParams p;
  p.leak_cm3_s_per_bar = 0;
  const HaldexHydraulics h(p, kPackNmPerN);
  for (const auto& [slip_rad_s, opening] : {std::pair{5.0, 0.2}, std::pair{2.0, 0.05}, std::pair{20.0, 1.0}}) {
    const double flow = displacement_m3_per_rad(p) * slip_rad_s;
    const double velocity = flow / (p.discharge_coefficient * opening * p.valve_area_mm2 * 1e-6);
    const double expected_bar = 0.5 * p.oil_density_kg_m3 * velocity * velocity / 1e5;
    ASSERT_LT(expected_bar, p.relief_pressure_bar);
    ASSERT_GT(expected_bar, HaldexHydraulics::kLaminarPressure_bar);
    // The rate vanishes there (relative to the pump's own rate) ...
    const double pump_bar_s = flow / compliance_m3_per_Pa(p) / 1e5;
    EXPECT_NEAR(h.pressure_rate_bar_s(expected_bar, slip_rad_s, opening, 1e9), 0.0, 1e-12 * pump_bar_s);
    // ... and a pressure starting at zero settles on it: 100 s, > 29 of the linearised time
    // constants 2pC/Q (3.4 s at the slowest), so converged to 1e-9.
    EXPECT_NEAR(integrate_bar(h, 0.0, slip_rad_s, opening, 1e9, 1.0, 100.0), expected_bar, 1e-9 * expected_bar)
        << slip_rad_s << " " << opening;
    EXPECT_NEAR(h.steady_pressure_bar(slip_rad_s, opening), expected_bar, 1e-12 * expected_bar);
  }
  // With the laminar leakage too: G p + K √p = Q, solved here as a quadratic in √p.
  const HaldexHydraulicsParams leaky;
  const HaldexHydraulics hl(leaky, kPackNmPerN);
  const double q = displacement_m3_per_rad(leaky) * 5.0;
  const double k =
      leaky.discharge_coefficient * 0.2 * leaky.valve_area_mm2 * 1e-6 * std::sqrt(2 / leaky.oil_density_kg_m3);
  const double g = leaky.leak_cm3_s_per_bar * 1e-6 / 1e5;
  const double root = (-k + std::sqrt(k * k + 4 * g * q)) / (2 * g);
  EXPECT_NEAR(hl.steady_pressure_bar(5.0, 0.2), root * root / 1e5, 1e-9 * root * root / 1e5);
}

TEST(HaldexHydraulics, OrificeTurnsLaminarBelowTheTransitionPressureAndStaysContinuous) {
  HaldexHydraulicsParams p;
  p.leak_cm3_s_per_bar = 0;
  const HaldexHydraulics h(p, kPackNmPerN);
  const double k = p.discharge_coefficient * p.valve_area_mm2 * 1e-6 * std::sqrt(2 / p.oil_density_kg_m3);
  const double c = compliance_m3_per_Pa(p);
  const double lam_Pa = 0.01 * 1e5;
  // Below p_lam: Q = k u p/√p_lam, linear in p (so the decay is exponential, not finite-time).
  for (double pressure_bar : {0.002, 0.005})
    EXPECT_NEAR(h.pressure_rate_bar_s(pressure_bar, 0.0, 0.5, 1e9),
                -k * 0.5 * pressure_bar * 1e5 / std::sqrt(lam_Pa) / c / 1e5, 1e-12 * k * 0.5 * 1e5 / c);
  // Both regimes give the same flow at p_lam.
  const double below = h.pressure_rate_bar_s(0.01 * (1 - 1e-12), 0.0, 1.0, 1e9);
  const double above = h.pressure_rate_bar_s(0.01, 0.0, 1.0, 1e9);
  EXPECT_NEAR(below, above, 1e-9 * std::abs(above));
  // A small pump flow settles in the laminar regime at Q √p_lam / (k u).
  const double slip_rad_s = 0.01;
  const double q = displacement_m3_per_rad(p) * slip_rad_s;
  const double expected_bar = q * std::sqrt(lam_Pa) / k / 1e5;
  ASSERT_LT(expected_bar, 0.01);
  EXPECT_NEAR(h.steady_pressure_bar(slip_rad_s, 1.0), expected_bar, 1e-12 * expected_bar);
  EXPECT_NEAR(integrate_bar(h, 0.0, slip_rad_s, 1.0, 1e9, 1.0, 1.0), expected_bar, 1e-9 * expected_bar);
}

TEST(HaldexHydraulics, ShutValveDecaysWithTheComplianceTimeConstant) {
  for (double leak : {0.005, 0.05}) {
    HaldexHydraulicsParams p;
    p.leak_cm3_s_per_bar = leak;
    const HaldexHydraulics h(p, kPackNmPerN);
    const double tau_s = compliance_m3_per_Pa(p) / (leak * 1e-6 / 1e5);
    EXPECT_NEAR(integrate_bar(h, 20.0, 0.0, 0.0, 1e9, 1.0, 1.0), 20.0 * std::exp(-1.0 / tau_s), 1e-9 * 20.0) << tau_s;
    // The oil at twice the viscosity leaks half as fast: leak_scale = ν(40)/ν(T) = 0.5.
    EXPECT_NEAR(integrate_bar(h, 20.0, 0.0, 0.0, 1e9, 0.5, 1.0), 20.0 * std::exp(-0.5 / tau_s), 1e-9 * 20.0);
  }
}

TEST(HaldexHydraulics, ReliefValveAndSettingCapThePressureAndTheForceIsAreaTimesPressure) {
  const HaldexHydraulicsParams p;
  const HaldexHydraulics h(p, kPackNmPerN);
  // Valve shut at 100 rad/s: the pressure settles where the pump's flow leaves through the
  // leakage and the relief valve, D ω = G p + (C/τ_r)(p − p_cap), on the setting or the relief
  // pressure, whichever is lower.
  const double c = compliance_m3_per_Pa(p), g = p.leak_cm3_s_per_bar * 1e-6 / 1e5;
  const double q = displacement_m3_per_rad(p) * 100.0, kr = c / HaldexHydraulics::kReliefTime_s;
  for (const auto& [setting_bar, cap_bar] : {std::pair{12.0, 12.0}, std::pair{80.0, 30.0}}) {
    const double expected_bar = (q + kr * cap_bar * 1e5) / (g + kr) / 1e5;
    EXPECT_GT(expected_bar, cap_bar);  // the override, Q τ_r / C: 0.7 bar at this (extreme) slip
    EXPECT_NEAR(integrate_bar(h, 0.0, 100.0, 0.0, setting_bar, 1.0, 0.5), expected_bar, 1e-9 * expected_bar);
  }
  // Above a lowered cap the relief valve brings it down with its own time constant.
  EXPECT_NEAR(h.pressure_rate_bar_s(5.0, 0.0, 0.0, 0.0), -5.0 / HaldexHydraulics::kReliefTime_s - g * 5.0 / c, 1e-9);
  EXPECT_NEAR(integrate_bar(h, 5.0, 0.0, 0.0, 0.0, 1.0, 0.05, 1e-5), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(h.pressure_rate_bar_s(0.0, 0.0, 1.0, 30.0), 0.0);  // no slip, no pressure
  // Gen I: no preload spring; F = A p. The default pack then carries n μ r A = 54 N m per bar.
  EXPECT_DOUBLE_EQ(h.clamp_force_N(0.0), 0.0);
  EXPECT_NEAR(h.clamp_force_N(10.0), p.piston_area_cm2 * 1e-4 * 1e6, 1e-9);
  EXPECT_NEAR(h.pressure_for_force_bar(h.clamp_force_N(7.5)), 7.5, 1e-12);
  HaldexHydraulicsParams spring = p;
  spring.preload_torque_Nm = 80.0;
  const HaldexHydraulics sprung(spring, kPackNmPerN);
  EXPECT_NEAR(sprung.clamp_force_N(0.0), 80.0 / kPackNmPerN, 1e-9);
  EXPECT_DOUBLE_EQ(sprung.pressure_for_force_bar(0.5 * sprung.clamp_force_N(0.0)), 0.0);  // the spring alone
}

TEST(HaldexHydraulics, RejectsNonPhysicalParameters) {
  for (double HaldexHydraulicsParams::*field :
       {&HaldexHydraulicsParams::relief_pressure_bar, &HaldexHydraulicsParams::piston_area_cm2,
        &HaldexHydraulicsParams::pump_displacement_cm3_per_rev, &HaldexHydraulicsParams::chamber_volume_cm3,
        &HaldexHydraulicsParams::bulk_modulus_bar, &HaldexHydraulicsParams::pack_stiffness_N_per_mm,
        &HaldexHydraulicsParams::discharge_coefficient, &HaldexHydraulicsParams::oil_density_kg_m3,
        &HaldexHydraulicsParams::valve_time_constant_ms}) {
    HaldexHydraulicsParams p;
    p.*field = 0.0;
    EXPECT_THROW(HaldexHydraulics(p, kPackNmPerN), std::invalid_argument);
  }
  HaldexHydraulicsParams p;
  p.leak_cm3_s_per_bar = -1;
  EXPECT_THROW(HaldexHydraulics(p, kPackNmPerN), std::invalid_argument);
}

}  // namespace
}  // namespace shudder::components
