// The all-wheel-drive driveline with its Haldex coupling (rig_models/haldex_driveline) against
// conservation laws and closed forms:
//   * Newton: driving straight with the coupling locked, every part turns with the car (rolling
//     ratios s_i), so the car accelerates as if one inertia J_eq = Σ J_i s_i² were driven by the
//     engine torque through s_engine: ω_v(t) = ω_v(0) + T s_engine t / J_eq;
//   * energy: engine work = kinetic + elastic energy + coupling heat + damper losses;
//   * tight turn: the front axle travels ρ times the rear's path. With the coupling locked both
//     axles turn together at ω_w, so the tyres take up the mismatch by slip; with no engine
//     torque the axles' torques cancel (up to the car's slow deceleration), which gives the
//     circulating torque on the rear axle T_r = c_f c_r / (c_f + c_r) (ρ − 1) ω_v,
//     c = 2 C_κ r² / v_ref per axle.
//   * an open coupling (valve shut, no preload) carries nothing to the rear axle;
//   * the estimates put the locked shuffle mode in PHYSICS.md's 2–10 Hz;
//   * in a tight turn fluid C keeps the coupling sliding smoothly, a fluid with a high static
//     friction makes it stick-slip, at the frequency the stick events give.
#include <gtest/gtest.h>

#include <cmath>

#include "io/fluid_loader.hpp"
#include "io/scenario.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "tests/support/recording.hpp"

namespace shudder::rig_models {
namespace {

// The LSC disc (fluid C) of the rig scenarios as the coupling's pack: 16 sliding interfaces
// (about eight friction discs; estimate).
io::Scenario pack_scenario(const std::string& fluid) {
  io::Scenario sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/rig_case1_25kN_378Hz.toml");
  if (!fluid.empty()) sc.fluid = io::load_fluid(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/fluids/" + fluid);
  sc.clutch.sliding_interfaces = 16;
  sc.clutch.start_temp_C = sc.clutch.sump_start_temp_C = 40.0;
  return sc;
}

struct Pack {
  explicit Pack(const std::string& fluid = "") : sc(pack_scenario(fluid)), clutch(sc.make_clutch()) {}
  io::Scenario sc;
  clutch::WetClutch clutch;
};

double last(const dynamics::Recording& r, const char* name) { return test::signal(r, name).back(); }

TEST(HaldexDriveline, LockedStraightDrivingAcceleratesLikeOneInertia) {
  const Pack pack;
  DrivelineParams p;
  p.hydraulics.preload_torque_Nm = 5000.0;  // locked throughout: a test of the network
  DrivelineInputs in;
  in.engine_torque_Nm = PiecewiseLinear({0.0}, {100.0});
  in.start_speed_km_h = 10.0;
  DrivelineSettings s;
  s.duration_s = 3.0;
  const auto rec = run_driveline(p, pack.clutch, in, s);

  const HaldexDriveline dl(p, pack.clutch, in);
  const Eigen::VectorXd ratio = dl.rolling_speed_ratios();
  double j_eq = 0;
  for (int i = 0; i < ratio.size(); ++i) j_eq += dl.network().inertias()[i].inertia_kg_m2 * ratio[i] * ratio[i];
  const double w0 = 10.0 / 3.6 / p.wheel_radius_m;
  const double w_expected = w0 + 100.0 * ratio[HaldexDriveline::kEngine] * 3.0 / j_eq;
  const double w_end = last(rec, "vehicle_speed_km_h") / 3.6 / p.wheel_radius_m;
  // The torque step rings the shuffle mode; the tyre slip damps it, and what is left, plus the
  // steady tyre slip and twist, is well under 0.5 % of the speed gained.
  EXPECT_NEAR(w_end, w_expected, 0.005 * (w_expected - w0));
  EXPECT_EQ(last(rec, "stuck"), 1.0);
  EXPECT_LT(test::scalar(rec, "mechanical_energy_relative_error"), 1e-4);
  // The estimated parameters must put the shuffle mode where PHYSICS.md §8 says vehicles have
  // it (2–10 Hz); 3.7 Hz with these defaults.
  EXPECT_GT(test::scalar(rec, "shuffle_frequency_Hz"), 2.0);
  EXPECT_LT(test::scalar(rec, "shuffle_frequency_Hz"), 10.0);
}

TEST(HaldexDriveline, TightTurnCirculatesTheClosedFormTorque) {
  const Pack pack;
  DrivelineParams p;
  p.turn_ratio = 1.04;
  p.hydraulics.leak_time_constant_s = 1e6;  // the pressure, once built, holds: the coupling locks
  DrivelineInputs in;
  in.start_speed_km_h = 5.0;
  DrivelineSettings s;
  s.duration_s = 4.0;
  const auto rec = run_driveline(p, pack.clutch, in, s);
  ASSERT_EQ(last(rec, "stuck"), 1.0) << "the coupling should have locked";
  const double c_axle = 2 * p.tyre_slip_stiffness_N * p.wheel_radius_m * p.wheel_radius_m / p.tyre_reference_speed_m_s;
  const double w_v = last(rec, "vehicle_speed_km_h") / 3.6 / p.wheel_radius_m;
  const double expected = 0.5 * c_axle * (p.turn_ratio - 1.0) * w_v;
  // Quasi-static: the car slows by the tyre scrub (~1 %/s), whose inertial torque is < 2 % of T_r.
  EXPECT_NEAR(last(rec, "rear_axle_torque_Nm"), expected, 0.02 * expected);
  EXPECT_NEAR(last(rec, "front_axle_torque_Nm"), -expected, 0.02 * expected);
  EXPECT_LT(test::scalar(rec, "mechanical_energy_relative_error"), 1e-4);
}

TEST(HaldexDriveline, OpenCouplingDrivesTheFrontAxleOnly) {
  const Pack pack;
  DrivelineParams p;
  p.hydraulics.preload_torque_Nm = 0.0;
  p.turn_ratio = 1.04;  // slip pumps, but the valve is shut
  DrivelineInputs in;
  in.engine_torque_Nm = PiecewiseLinear({0.0}, {80.0});
  in.valve_pressure_bar = PiecewiseLinear({0.0}, {0.0});
  in.start_speed_km_h = 5.0;
  DrivelineSettings s;
  s.duration_s = 1.0;
  const auto rec = run_driveline(p, pack.clutch, in, s);
  EXPECT_EQ(last(rec, "pressure_bar"), 0.0);
  EXPECT_NEAR(last(rec, "coupling_torque_Nm"), 0.0, 1e-9);
  // The rear wheels are only carried along by the road: their half-shafts accelerate the rear
  // diff and the coupling's rear half, a few N m at most.
  EXPECT_LT(std::abs(last(rec, "rear_axle_torque_Nm")), 5.0);
  EXPECT_GT(last(rec, "front_axle_torque_Nm"), 0.5 * 80.0 * p.gear_ratio * p.final_drive_ratio);
}

// The shipped tight turn (scenarios/driveline_tight_turn.toml) with fluid C and with a fluid
// whose static friction is 1.3 × its kinetic (schematic_stick_slip): only the second may make
// the coupling stick-slip, and the frequency the FFT finds must agree with the stick-slip
// events counted in the time domain. The count is over the whole oscillating part while the
// pressure (and so the cycle) still changes, the FFT peak weights the strongest stretch: 15 %.
dynamics::Recording tight_turn(const Pack& pack) {
  DrivelineParams p;
  p.turn_ratio = 1.04;
  DrivelineInputs in;
  in.engine_torque_Nm = PiecewiseLinear({0.0, 0.5, 5.0}, {0.0, 30.0, 30.0});
  in.start_speed_km_h = 5.0;
  DrivelineSettings s;
  s.duration_s = 5.0;
  return run_driveline(p, pack.clutch, in, s);
}

TEST(HaldexDriveline, TightTurnStickSlipsOnlyWithAHighStaticFriction) {
  const auto smooth = tight_turn(Pack());
  EXPECT_EQ(test::scalar(smooth, "coupling_verdict_code"), 0.0) << "fluid C must not judder";

  const auto rough = tight_turn(Pack("schematic_stick_slip.toml"));
  ASSERT_EQ(test::scalar(rough, "coupling_verdict_code"), 2.0) << "stick_slip expected";
  const auto& t = test::signal(rough, "time_s");
  const auto& stuck = test::signal(rough, "stuck");
  int breakaways = 0;
  double first = -1, last_t = -1;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (stuck[i - 1] == 1.0 && stuck[i] == 0.0) {
      ++breakaways;
      if (first < 0) first = t[i];
      last_t = t[i];
    }
  ASSERT_GT(breakaways, 10);
  const double event_rate_Hz = (breakaways - 1) / (last_t - first);
  EXPECT_NEAR(test::scalar(rough, "coupling_oscillation_frequency_Hz"), event_rate_Hz, 0.15 * event_rate_Hz);
}

TEST(HaldexDriveline, RejectsNonPhysicalParameters) {
  const Pack pack;
  DrivelineParams p;
  p.turn_ratio = 0;
  EXPECT_THROW(HaldexDriveline(p, pack.clutch, {}), std::invalid_argument);
  p = {};
  p.belt_share = 1.0;
  EXPECT_THROW(HaldexDriveline(p, pack.clutch, {}), std::invalid_argument);
}

}  // namespace
}  // namespace shudder::rig_models
