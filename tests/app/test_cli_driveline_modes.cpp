// `shudder modes` on a driveline scenario: the linearisation about the
// manoeuvre's quasi-static point, coupling slipping and locked, modes named by component.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>

#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;

// The shipped tight turn with fluid C: a rising friction curve, so every mode is damped. Its raw
// valve setting (30 bar, the valve shut below it) lets the pump build the full setting at any
// slip in the steady state, so the operating point's clamp force is A p = 60 cm² × 30 bar =
// 18000 N (Gen I: no preload) plus the relief valve's override at that slip, D|Δω| τ_r/C ≈
// 0.02 bar (12 N at the point's 38 rpm: the tyres' slip stiffness c_κ F_z, tyre.hpp, lets them
// take more of the turn's kinematic slip), and the tyres carry the wound-up torque (≈5.7 kN each).
TEST(CliDrivelineModes, TightTurnReportsSlippingAndLockedModesByComponent) {
  const auto dir = scratch_dir("dl_modes");
  const auto r = run_cli("modes '" + source_path("scenarios/driveline_tight_turn.toml") + "'", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("driveline linearised at 5 km/h"));
  EXPECT_THAT(r.out, HasSubstr("Coupling slipping:"));
  EXPECT_THAT(r.out, HasSubstr("Coupling locked:"));
  EXPECT_THAT(r.out, HasSubstr("wheel_rl"));
  EXPECT_THAT(r.out, HasSubstr("clamp force 18012 N"));
  EXPECT_THAT(r.out, HasSubstr("stable"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("UNSTABLE")));
}

// The negative-slope fluid in a turn at 10 km/h: the coupling's output side judders. At a 2 bar
// setting (1.2 kN): at 1 bar (0.6 kN) the tyres' slip, with the load-proportional slip stiffness
// of tyre.hpp, damps the coupling's modes enough that the point is stable (measured: least
// damped 2.69 Hz, −0.83 1/s); at 2 bar the coupling's output side with the rear differential
// grows at +16.1 1/s, 44.7 Hz.
TEST(CliDrivelineModes, NegativeSlopeTakeUpIsPredictedUnstable) {
  const auto dir = scratch_dir("dl_modes_neg");
  std::string s = slurp(source_path("scenarios/driveline_tight_turn.toml"));
  s = replace(s, "fluids/lsc_fluid_c.toml", source_path("scenarios/fluids/schematic_negative_slope.toml"));
  s = replace(s, "start_speed_km_h = 5.0", "start_speed_km_h = 10.0");
  s = replace(s, "valve_pressure_bar = 30.0", "valve_pressure_bar = 2.0");
  s = replace(s, "turn_radius_m = 9.0", "turn_radius_m = 6.0");
  write_file(dir / "s.toml", s);
  const auto r = run_cli("modes s.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("UNSTABLE (judder predicted)"));
  EXPECT_THAT(r.out, HasSubstr("coupling_out +1.00 rear_diff"));
}

// One linearisation for a run: the summary's locked shuffle mode and `modes --run` on the same
// run print the same mode (frequency and damping ratio to the printed digits), linearised at the
// run's mean operating point, not at the manoeuvre's quasi-static one.
TEST(CliDrivelineModes, RunSummaryAndModesAtTheRunAgree) {
  const auto dir = scratch_dir("dl_modes_run");
  std::string scenario = "'";
  scenario += source_path("scenarios/driveline_tight_turn.toml");
  scenario += "'";
  const auto run = run_cli("run " + scenario + " -o tight.h5", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto at = run.out.find("locked shuffle mode ");
  ASSERT_NE(at, std::string::npos) << run.out;
  double f_Hz = 0, zeta = 0;
  ASSERT_EQ(std::sscanf(run.out.c_str() + at, "locked shuffle mode %lf Hz (damping ratio %lf)", &f_Hz, &zeta), 2);
  const auto modes = run_cli("modes " + scenario + " --run tight.h5", dir);
  ASSERT_EQ(modes.exit_code, 0) << modes.err;
  EXPECT_THAT(modes.out, HasSubstr("At the mean operating point of tight.h5"));
  // The locked table's first oscillating row above 0.5 Hz.
  const auto locked = modes.out.find("Coupling locked:");
  ASSERT_NE(locked, std::string::npos);
  std::istringstream rows(modes.out.substr(modes.out.find('\n', modes.out.find('\n', locked) + 1) + 1));
  std::string row;
  double found_Hz = -1, found_zeta = -1;
  while (std::getline(rows, row) && !row.empty()) {
    double re = 0, im = 0, f = 0, z = 0;
    if (std::sscanf(row.c_str(), "%lf %lf %lf %lf", &re, &im, &f, &z) == 4 && im > 0 && f > 0.5) {
      found_Hz = f;
      found_zeta = z;
      break;
    }
  }
  EXPECT_NEAR(found_Hz, f_Hz, 0.006) << modes.out;     // the summary prints 2 decimals
  EXPECT_NEAR(found_zeta, zeta, 0.0006) << modes.out;  // and 3
  // --run on another kind says why in one line.
  const auto refused =
      run_cli("modes '" + source_path("scenarios/rig_case1_25kN_378Hz.toml") + "' --run tight.h5", dir);
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_THAT(refused.err, HasSubstr("--run"));
}
