// `shudder run` on a driveline scenario (type = "driveline": the AWD car with its Haldex
// coupling) end to end, and the inputs a driveline scenario must refuse (exit 2, one line
// naming the file and key).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "io/hdf5_run.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/recording.hpp"

namespace shudder {
namespace {

using test::expect_rejected;
using test::replace;
using test::run_cli;
using test::scratch_dir;
using test::slurp;
using test::source_path;
using test::write_file;
using ::testing::HasSubstr;

std::string tight_turn(const std::string& extra = "") {
  return test::shipped_scenario_text("driveline_tight_turn.toml") + extra;
}

TEST(CliDriveline, RunsTheTightTurnAndWritesItsSignals) {
  const auto dir = scratch_dir("cli_driveline_ok");
  write_file(dir / "turn.toml", tight_turn());
  const auto r = run_cli("run turn.toml -o turn.h5 --report rep", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("(driveline)"));
  EXPECT_THAT(r.out, HasSubstr("coupling slip [rpm]"));
  EXPECT_THAT(r.out, HasSubstr("locked shuffle mode"));
  EXPECT_THAT(r.out, HasSubstr("Coupling judder: none"));  // fluid C slides smoothly
  EXPECT_TRUE(std::filesystem::exists(dir / "rep" / "coupling.png"));
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;  // no rig plot attempted
  const auto rec = io::read_run_hdf5((dir / "turn.h5").string());
  // The size guard's count (app/output_size.hpp, docs/formats/run_output.md): 27 channels.
  EXPECT_EQ(rec.signals.size(), 27u);
  // At the start the car rolls at 5 km/h and the axles differ by the turn: the coupling slips at
  // i_ptu (ρ̄_f − ρ̄_r) ω_v, ρ̄_f the front wheels' mean path ratio on R = 9 m (wheelbase 2.51 m,
  // track 1.51 m), ρ̄_r = 1.
  const double rho_f = 0.5 * (std::hypot(2.51, 9.0 - 0.755) + std::hypot(2.51, 9.0 + 0.755)) / 9.0;
  EXPECT_NEAR(test::signal(rec, "coupling_slip_rpm").front(),
              2.6 * (rho_f - 1.0) * 5 / 3.6 / 0.32 * 60 / (2 * 3.14159265358979), 1e-6);
  // The pump turns that slip into pressure, and the pack's torque follows it.
  EXPECT_GT(test::signal(rec, "pressure_bar").back(), 1.0);
  EXPECT_GT(test::signal(rec, "coupling_torque_Nm").back(), test::signal(rec, "coupling_torque_Nm").front());
}

TEST(CliDriveline, RejectsATurnRatioBelowOne) {
  expect_rejected(test::run_scenario_in("cli_driveline_turn", replace(tight_turn("\n[driveline]\nturn_ratio = 0.9\n"),
                                                                      "turn_radius_m = 9.0", "")),
                  {"s.toml", "turn_ratio", "[1, 1.2]"});
}

// Bad input a user can give: impossible geometry, road μ <= 0, a valve setting beyond the relief
// valve, a rig-only effect on a car: exit 2, one line naming file and key.
TEST(CliDriveline, RejectsATurnInsideHalfTheTrack) {
  expect_rejected(test::run_scenario_in("cli_driveline_radius",
                                        replace(tight_turn(), "turn_radius_m = 9.0", "turn_radius_m = 0.7")),
                  {"s.toml", "turn_radius_m", "(0.755, 10000]"});
}

TEST(CliDriveline, RejectsBothTurnKeys) {
  expect_rejected(test::run_scenario_in("cli_driveline_both", tight_turn("\n[driveline]\nturn_ratio = 1.04\n")),
                  {"s.toml", "turn_radius_m", "either"});
}

// The tyres' slip stiffness: c_κ F_z or an absolute C_κ, not both (components/tyre.hpp).
TEST(CliDriveline, RejectsBothTyreSlipStiffnesses) {
  expect_rejected(
      test::run_scenario_in("cli_driveline_kappa", tight_turn("\n[driveline]\ntyre_slip_stiffness_N = 1.5e5\n"
                                                              "tyre_slip_stiffness_per_load = 19.0\n")),
      {"s.toml", "tyre_slip_stiffness_per_load", "an alternative to tyre_slip_stiffness_N"});
}

TEST(CliDriveline, RejectsANonPositiveRoadFriction) {
  expect_rejected(test::run_scenario_in("cli_driveline_mu", tight_turn("\n[road]\nfriction = [0.1, 0.0, 1.0, 1.0]\n")),
                  {"s.toml", "friction", "(0, 2]"});
  expect_rejected(test::run_scenario_in("cli_driveline_mu3", tight_turn("\n[road]\nfriction = [0.1, 1.0, 1.0]\n")),
                  {"s.toml", "friction", "four (FL, FR, RL, RR)"});
}

TEST(CliDriveline, RejectsAValveSettingBeyondTheRelief) {
  expect_rejected(test::run_scenario_in("cli_driveline_valve", replace(tight_turn(), "valve_pressure_bar = 30.0",
                                                                       "valve_pressure_bar = 31.0")),
                  {"s.toml", "valve_pressure_bar", "[0, 30]"});
}

TEST(CliDriveline, RejectsARigOnlyEffect) {
  expect_rejected(
      test::run_scenario_in("cli_driveline_effect", tight_turn("\n[effects.bearing_drag]\nenabled = true\n")),
      {"s.toml", "bearing_drag", "torque-cell bearing"});
}

TEST(CliDriveline, RejectsAThrottleWithATorqueScheduleOrAStalledStart) {
  expect_rejected(test::run_scenario_in("cli_driveline_throttle", replace(tight_turn(), "valve_pressure_bar = 30.0",
                                                                          "valve_pressure_bar = 30.0\nthrottle = 0.2")),
                  {"s.toml", "throttle", "either"});
  const std::string mapped = replace(replace(tight_turn(), "engine_torque_Nm = [0.0, 30.0, 30.0]", "throttle = 0.1"),
                                     "start_speed_km_h = 5.0", "start_speed_km_h = 2.0");
  expect_rejected(test::run_scenario_in("cli_driveline_stalled", mapped),
                  {"s.toml", "start_speed_km_h", "stall speed"});
}

TEST(CliDriveline, RejectsARoadTableOnARig) {
  expect_rejected(test::run_scenario_in("cli_rig_road", test::shipped_scenario_text("rig_stick_slip.toml") +
                                                            "\n[road]\nfriction = [1.0]\n"),
                  {"s.toml", "road", "driveline"});
}

TEST(CliDriveline, RejectsARigDriveCycle) {
  expect_rejected(
      test::run_scenario_in("cli_driveline_drive",
                            tight_turn("\n[drive]\ntime_s = [0.0]\nspeed_rpm = 1.0\nnormal_force_N = 1000.0\n")),
      {"s.toml", "drive", "[manoeuvre]"});
}

// A driveline writes its coupling's measured run (was refused: "a measured run
// is a rig log"); tests/app/test_diagnose_driveline.cpp checks its columns.
TEST(CliDriveline, WritesTheCouplingsMeasuredRun) {
  const auto dir = scratch_dir("cli_driveline_measurement");
  write_file(dir / "turn.toml", tight_turn());
  const auto r = run_cli("run turn.toml --measurement m.csv", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(test::slurp(dir / "m.csv"), ::testing::HasSubstr("# rig: haldex_coupling\n"));
}

}  // namespace
}  // namespace shudder
