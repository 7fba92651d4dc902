// `shudder modes` on a driveline scenario: the linearisation about the
// manoeuvre's quasi-static point, coupling slipping and locked, modes named by component.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;

// The shipped tight turn with fluid C: a rising friction curve, so every mode is damped. Its raw
// valve setting (30 bar, the valve shut below it) lets the pump build the full setting at any
// slip in the steady state, so the operating point's clamp force is A p = 60 cm² × 30 bar =
// 18000 N (Gen I: no preload) plus the relief valve's override at that slip, D|Δω| τ_r/C ≈
// 0.007 bar (4 N), and the tyres carry the wound-up torque (≈5.4 kN each).
TEST(CliDrivelineModes, TightTurnReportsSlippingAndLockedModesByComponent) {
  const auto dir = scratch_dir("dl_modes");
  const auto r = run_cli("modes '" + source_path("scenarios/driveline_tight_turn.toml") + "'", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("driveline linearised at 5 km/h"));
  EXPECT_THAT(r.out, HasSubstr("Coupling slipping:"));
  EXPECT_THAT(r.out, HasSubstr("Coupling locked:"));
  EXPECT_THAT(r.out, HasSubstr("wheel_rl"));
  EXPECT_THAT(r.out, HasSubstr("clamp force 18004 N"));
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
