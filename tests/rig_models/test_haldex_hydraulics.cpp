// The first-generation Haldex hydraulics (rig_models/haldex_hydraulics) against closed forms of
//   C dp/dt = D|Δω| − C_d u a √(2p/ρ) − G p,   0 <= p <= min(p_relief, p_set),   C = V/β + A²/k:
//   * valve shut, no leakage: p = D φ / C after a relative rotation φ (the pump's flow ∝ |Δω|),
//     and the defaults reach the relief after a quarter turn of the WHEEL (2.6 × π/2 at the coupling);
//   * constant |Δω| with the valve open by u: the orifice equation's static pressure
//     p = ρ/2 (D|Δω| / (C_d u a))², and with leakage the root of G p + C_d u a √(2p/ρ) = D|Δω|;
//   * no rotation, valve shut: p0 e^(−t G/C) (the compliance time constant), and twice as fast
//     with half the viscosity;
//   * the relief valve and a pressure setting cap the pressure; F = A p (Gen I: no preload).
// Every expected value is computed here from the parameters, not from the class's getters.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rig_models/haldex_hydraulics.hpp"

namespace shudder::rig_models {
namespace {

constexpr double kPackNmPerN = 16 * 0.12 * 0.04725;  // n μ r_eff of the 16-interface LSC pack

double displacement_m3_per_rad(const HaldexHydraulicsParams& p) {
  return p.pump_displacement_cm3_per_rev * 1e-6 / (2 * std::numbers::pi);
}
double compliance_m3_per_Pa(const HaldexHydraulicsParams& p) {
  const double area = p.piston_area_cm2 * 1e-4;
  return p.chamber_volume_cm3 * 1e-6 / (p.bulk_modulus_bar * 1e5) + area * area / (p.pack_stiffness_N_per_mm * 1e3);
}

TEST(HaldexHydraulics, ShutValveBuildsPumpVolumeOverComplianceAndFullPressureAfterAQuarterWheelTurn) {
  HaldexHydraulicsParams p;
  p.leak_cm3_s_per_bar = 0;
  const HaldexHydraulics h(p, kPackNmPerN);
  // A constant pumping rate with nothing leaving: backward Euler is exact for a linear rise.
  const double slip_rad_s = 3.0;
  double pressure = 0;
  for (int k = 0; k < 10; ++k) pressure = h.step_pressure_bar(pressure, slip_rad_s * 0.01, 0.01, 0.0, 1e9);
  const double expected_bar = displacement_m3_per_rad(p) * slip_rad_s * 0.1 / compliance_m3_per_Pa(p) / 1e5;
  EXPECT_NEAR(pressure, expected_bar, 1e-12 * expected_bar);
  // Twice the speed difference: twice the flow.
  EXPECT_NEAR(h.step_pressure_bar(0, 2 * slip_rad_s * 0.01, 0.01, 0.0, 1e9),
              2 * h.step_pressure_bar(0, slip_rad_s * 0.01, 0.01, 0.0, 1e9), 1e-12);
  // Public: full engagement after a quarter turn of the wheel; the coupling turns i_r = 2.6 times
  // the rear wheel. The defaults were set for it: within 1 % (0.3 % by the parameters' rounding).
  const double quarter_wheel_turn_rad = 2.6 * std::numbers::pi / 2;
  const double p_quarter_bar = displacement_m3_per_rad(p) * quarter_wheel_turn_rad / compliance_m3_per_Pa(p) / 1e5;
  EXPECT_NEAR(p_quarter_bar / p.relief_pressure_bar, 1.0, 0.01);
  // The relief valve passes the rest.
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(0, 2 * quarter_wheel_turn_rad, 0.01, 0.0, 1e9), p.relief_pressure_bar);
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
    double pressure = 0;
    for (int k = 0; k < 10000; ++k) pressure = h.step_pressure_bar(pressure, slip_rad_s * 0.01, 0.01, opening, 1e9);
    // 100 s, > 29 of the linearised time constants 2pC/Q (3.4 s at the slowest): converged (1e-9).
    EXPECT_NEAR(pressure, expected_bar, 1e-9 * expected_bar) << slip_rad_s << " " << opening;
    EXPECT_NEAR(h.steady_pressure_bar(slip_rad_s, opening), expected_bar, 1e-12 * expected_bar);
  }
  // With the laminar leakage too: G p + K √p = Q, solved here as a quadratic in √p.
  const HaldexHydraulicsParams leaky;
  const HaldexHydraulics hl(leaky, kPackNmPerN);
  const double q = displacement_m3_per_rad(leaky) * 5.0;
  const double k = leaky.discharge_coefficient * 0.2 * leaky.valve_area_mm2 * 1e-6 * std::sqrt(2 / leaky.oil_density_kg_m3);
  const double g = leaky.leak_cm3_s_per_bar * 1e-6 / 1e5;
  const double root = (-k + std::sqrt(k * k + 4 * g * q)) / (2 * g);
  EXPECT_NEAR(hl.steady_pressure_bar(5.0, 0.2), root * root / 1e5, 1e-9 * root * root / 1e5);
}

TEST(HaldexHydraulics, ShutValveDecaysWithTheComplianceTimeConstant) {
  for (double leak : {0.005, 0.05}) {
    HaldexHydraulicsParams p;
    p.leak_cm3_s_per_bar = leak;
    const HaldexHydraulics h(p, kPackNmPerN);
    const double tau_s = compliance_m3_per_Pa(p) / (leak * 1e-6 / 1e5);
    double pressure = 20.0;
    for (int k = 0; k < 100; ++k) pressure = h.step_pressure_bar(pressure, 0.0, 0.01, 0.0, 1e9);
    // Backward Euler in 0.5 ms sub-steps: relative error ≈ t h/(2τ²) (2e-4 at τ = 1.08 s), so 5e-4.
    EXPECT_NEAR(pressure, 20.0 * std::exp(-1.0 / tau_s), 5e-4 * 20.0 * std::exp(-1.0 / tau_s)) << tau_s;
    // The oil at twice the viscosity leaks half as fast: leak_scale = ν(40)/ν(T) = 0.5.
    double cold = 20.0;
    for (int k = 0; k < 100; ++k) cold = h.step_pressure_bar(cold, 0.0, 0.01, 0.0, 1e9, 0.5);
    EXPECT_NEAR(cold, 20.0 * std::exp(-0.5 / tau_s), 5e-4 * cold);
  }
}

TEST(HaldexHydraulics, ReliefValveAndSettingCapThePressureAndTheForceIsAreaTimesPressure) {
  const HaldexHydraulicsParams p;
  const HaldexHydraulics h(p, kPackNmPerN);
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(0.0, 100.0, 0.01, 0.0, 12.0), 12.0);  // the setting
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(0.0, 100.0, 0.01, 0.0, 80.0), 30.0);  // never above the relief
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(5.0, 0.0, 0.01, 0.0, 0.0), 0.0);      // a zero setting
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(0.0, 0.0, 0.01, 1.0, 30.0), 0.0);     // no slip, no pressure
  // Gen I: no preload spring; F = A p. The default pack then carries n μ r A = 54 N m per bar.
  EXPECT_DOUBLE_EQ(h.clamp_force_N(0.0), 0.0);
  EXPECT_NEAR(h.clamp_force_N(10.0), p.piston_area_cm2 * 1e-4 * 1e6, 1e-9);
  HaldexHydraulicsParams spring = p;
  spring.preload_torque_Nm = 80.0;
  EXPECT_NEAR(HaldexHydraulics(spring, kPackNmPerN).clamp_force_N(0.0), 80.0 / kPackNmPerN, 1e-9);
}

TEST(HaldexHydraulics, RejectsNonPhysicalParameters) {
  for (double HaldexHydraulicsParams::*field :
       {&HaldexHydraulicsParams::relief_pressure_bar, &HaldexHydraulicsParams::piston_area_cm2,
        &HaldexHydraulicsParams::pump_displacement_cm3_per_rev, &HaldexHydraulicsParams::chamber_volume_cm3,
        &HaldexHydraulicsParams::bulk_modulus_bar, &HaldexHydraulicsParams::pack_stiffness_N_per_mm,
        &HaldexHydraulicsParams::discharge_coefficient, &HaldexHydraulicsParams::oil_density_kg_m3}) {
    HaldexHydraulicsParams p;
    p.*field = 0.0;
    EXPECT_THROW(HaldexHydraulics(p, kPackNmPerN), std::invalid_argument);
  }
  HaldexHydraulicsParams p;
  p.leak_cm3_s_per_bar = -1;
  EXPECT_THROW(HaldexHydraulics(p, kPackNmPerN), std::invalid_argument);
}

}  // namespace
}  // namespace shudder::rig_models
