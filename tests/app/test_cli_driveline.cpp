// `shudder run` on a driveline scenario (type = "driveline": the AWD car with its Haldex
// coupling) end to end, and the inputs a driveline scenario must refuse (exit 2, one line
// naming the file and key).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/hdf5_run.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/recording.hpp"

namespace shudder {
namespace {

using ::testing::HasSubstr;
using test::expect_rejected;
using test::replace;
using test::run_cli;
using test::scratch_dir;
using test::slurp;
using test::source_path;
using test::write_file;

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
  // At the start the car rolls at 5 km/h and the axles differ by the turn: the coupling slips at
  // i_ptu (ρ − 1) ω_front_diff = 2.6 × 0.04 × (5/3.6/0.32 rad/s) = 4.31 rpm.
  EXPECT_NEAR(test::signal(rec, "coupling_slip_rpm").front(), 2.6 * 0.04 * 5 / 3.6 / 0.32 * 60 / (2 * 3.14159265358979),
              1e-6);
  // The pump turns that slip into pressure, and the pack's torque follows it.
  EXPECT_GT(test::signal(rec, "pressure_bar").back(), 1.0);
  EXPECT_GT(test::signal(rec, "coupling_torque_Nm").back(), test::signal(rec, "coupling_torque_Nm").front());
}

TEST(CliDriveline, RejectsATurnRatioBelowOne) {
  expect_rejected(test::run_scenario_in("cli_driveline_turn", replace(tight_turn(), "turn_ratio = 1.04", "turn_ratio = 0.9")),
                  {"s.toml", "turn_ratio", "[1, 1.2]"});
}

TEST(CliDriveline, RejectsARigDriveCycle) {
  expect_rejected(test::run_scenario_in("cli_driveline_drive", tight_turn("\n[drive]\ntime_s = [0.0]\nspeed_rpm = 1.0\nnormal_force_N = 1000.0\n")),
                  {"s.toml", "drive", "[manoeuvre]"});
}

TEST(CliDriveline, RefusesToWriteAMeasuredRun) {
  const auto dir = scratch_dir("cli_driveline_measurement");
  write_file(dir / "turn.toml", tight_turn());
  expect_rejected(run_cli("run turn.toml --measurement m.csv", dir), {"--measurement", "rig"});
}

}  // namespace
}  // namespace shudder
