// clutch/interface_thermal_impedance.hpp against its two closed-form limits, and the size of the
// thermal feedback on the coupling's friction slope (studies/driveline_stability.hpp) at
// a high-torque point and at the take-up judder onset.
#include "clutch/interface_thermal_impedance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

#include "io/scenario.hpp"
#include "studies/driveline_stability.hpp"
#include "rig_models/model.hpp"

namespace shudder::clutch {
namespace {

double effusivity(const Layer& l) {
  return std::sqrt(l.conductivity_W_per_mK * l.density_kg_m3 * l.specific_heat_J_per_kgK);
}

// Fast (penetration depth √(α/ω) ≪ every layer): two semi-infinite solids in parallel,
// Z = 1/((e_sep + e_lin) √(iω)) — the lining's wave never reaches the core.
TEST(InterfaceThermalImpedance, FastOscillationSeesTwoSemiInfiniteSolids) {
  const ThermalParams p;
  const double omega = 2 * std::numbers::pi * 5000.0;  // δ ≈ 0.03 mm in steel, 0.01 mm in the lining
  const std::complex<double> expected =
      1.0 / ((effusivity(p.separator) + effusivity(p.lining)) * std::sqrt(std::complex<double>(0.0, omega)));
  EXPECT_LT(std::abs(interface_thermal_impedance(p, omega) - expected),
            1e-9 * std::abs(expected));  // tanh → 1 to e^-40
}

// Slow (√(α/ω) ≫ every layer): the layers warm as one lump, Z = 1/(iω Σ ρ c L).
TEST(InterfaceThermalImpedance, SlowOscillationSeesTheLayersHeatCapacity) {
  const ThermalParams p;
  const double omega = 2 * std::numbers::pi * 0.01;  // δ ≈ 20 mm against 0.75 mm layers
  double capacity = 0;
  for (const Layer* l : {&p.separator, &p.lining, &p.core})
    capacity += l->density_kg_m3 * l->specific_heat_J_per_kgK * l->thickness_m;
  const std::complex<double> expected = 1.0 / std::complex<double>(0.0, omega * capacity);
  // Next term of the expansion: (ωL²/α)-order, ~1e-3 here.
  EXPECT_LT(std::abs(interface_thermal_impedance(p, omega) - expected), 5e-3 * std::abs(expected));
}

TEST(InterfaceThermalImpedance, RejectsNonPositiveFrequency) {
  EXPECT_THROW(interface_thermal_impedance(ThermalParams{}, 0.0), std::invalid_argument);
}

// The feedback's damping per interface, Re(s_eff) − s = n⁻¹ ... (driveline_stability.hpp), at
// the reviewer's point: 4 Hz, 125 N m per interface (16 interfaces, fluid C near 20 kN, 10 rpm,
// 60 °C), and at the rig's 378 Hz with the same torque. It must fall with frequency (|Re Z| ∝
// ω^-1/2 on a semi-infinite solid) and be destabilising (μ falls with temperature).
TEST(InterfaceThermalImpedance, ThermalFeedbackOnTheCouplingSlope) {
  io::Scenario sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_tight_turn.toml");
  sc.clutch.start_temp_C = 60.0;
  const WetClutch clutch = sc.make_clutch();
  const auto& model = std::get<rig_models::DrivelineModel>(sc.model);
  const rig_models::HaldexDriveline dl(model.params, clutch, model.manoeuvre);
  studies::DrivelineOperatingPoint op;
  op.interface_temp_C = 60.0;
  op.coupling_slip_rad_s = 10.0 * 2 * std::numbers::pi / 60.0;
  // Clamp force for 125 N m per interface (2 kN m for the pack): rescaled on the torque (μ
  // depends a little on the load).
  op.clamp_force_N = 20000.0;
  for (int i = 0; i < 4; ++i)
    op.clamp_force_N *= 2000.0 / studies::coupling_thermal_feedback(dl, clutch, op, 4.0).coupling_torque_Nm;
  const auto at4 = studies::coupling_thermal_feedback(dl, clutch, op, 4.0);
  const auto at378 = studies::coupling_thermal_feedback(dl, clutch, op, 378.0);
  EXPECT_NEAR(at4.coupling_torque_Nm, 2000.0, 1.0);  // the rescaling's fixed point
  std::printf(
      "thermal feedback per interface at 125 N m, %.0f N: 4 Hz %.4f, 378 Hz %.4f N m s/rad (isothermal "
      "%.4f); dM/dT %.3f N m/K for the pack\n",
      op.clamp_force_N, at4.added_damping_Nms / 16, at378.added_damping_Nms / 16, at4.isothermal_slope_Nms / 16,
      at4.torque_temperature_slope_Nm_per_K);
  EXPECT_LT(at4.added_damping_Nms, 0.0);
  EXPECT_LT(at378.added_damping_Nms, 0.0);
  // Semi-infinite scaling (√(378/4) ≈ 9.7) softened at 4 Hz, where the wave reaches the
  // separator's mid-plane (δ ≈ 0.73 mm against 0.75 mm).
  EXPECT_GT(at4.added_damping_Nms / at378.added_damping_Nms, 5.0);
}

}  // namespace
}  // namespace shudder::clutch
