// `shudder modes` on a driveline scenario (issue 13 part 4): the linearisation about the
// manoeuvre's quasi-static point, coupling slipping and locked, modes named by component.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;

// The shipped tight turn with fluid C: a rising friction curve, so every mode is damped; the
// half-shaft/wheel modes are at 32–37 Hz and the locked shuffle mode at ~3.7 Hz (the network's
// 3.71 Hz at rest, shifted by the tyres' slip damping at 5 km/h).
TEST(CliDrivelineModes, TightTurnReportsSlippingAndLockedModesByComponent) {
  const auto dir = scratch_dir("dl_modes");
  const auto r = run_cli("modes '" + source_path("scenarios/driveline_tight_turn.toml") + "'", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("driveline linearised at 5 km/h"));
  EXPECT_THAT(r.out, HasSubstr("Coupling slipping:"));
  EXPECT_THAT(r.out, HasSubstr("Coupling locked:"));
  EXPECT_THAT(r.out, HasSubstr("wheel_rl"));
  EXPECT_THAT(r.out, HasSubstr("3.685"));  // locked shuffle mode, Hz
  EXPECT_THAT(r.out, HasSubstr("stable"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("UNSTABLE")));
}

// The negative-slope fluid in a turn at 10 km/h: the coupling's output side judders.
TEST(CliDrivelineModes, NegativeSlopeTakeUpIsPredictedUnstable) {
  const auto dir = scratch_dir("dl_modes_neg");
  std::string s = slurp(source_path("scenarios/driveline_tight_turn.toml"));
  s = replace(s, "fluids/lsc_fluid_c.toml", source_path("scenarios/fluids/schematic_negative_slope.toml"));
  s = replace(s, "start_speed_km_h = 5.0", "start_speed_km_h = 10.0");
  s = replace(s, "valve_pressure_bar = 30.0", "valve_pressure_bar = 1.0");
  s = replace(s, "turn_radius_m = 9.0", "turn_radius_m = 6.0");
  write_file(dir / "s.toml", s);
  const auto r = run_cli("modes s.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("UNSTABLE (judder predicted)"));
  EXPECT_THAT(r.out, HasSubstr("coupling_out +1.00 rear_diff"));
}
