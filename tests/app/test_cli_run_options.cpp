// `shudder run` options: --set KEY=VALUE (the sweep's key names, parser and messages) changes
// the run, and options that would have no effect are refused instead of ignored.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/hdf5_run.hpp"
#include "tests/support/cli.hpp"

using namespace shudder;
using namespace shudder::test;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// Appended, not prefixed: GCC 12 at -O3 reports a false -Wrestrict on "'" + std::string.
std::string case1() {
  std::string quoted(1, '\'');
  quoted += source_path("scenarios/paper_g_case1_25kN.toml");
  quoted += '\'';
  return quoted;
}

}  // namespace

// The file says 25.3 kN from 77 °C; the run is made at 12 kN from 50 °C, and its HDF5 records
// the scenario as run.
TEST(CliRunOptions, SetChangesTheRunAndIsRecorded) {
  const auto dir = scratch_dir("run_set");
  const auto r =
      run_cli("run " + case1() + " -o out.h5 --set drive.normal_force_N=12000 --set clutch.start_temp_C=50", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rec = io::read_run_hdf5((dir / "out.h5").string());
  const auto* force = rec.find("normal_force_N");
  ASSERT_NE(force, nullptr);
  ASSERT_FALSE(force->values.empty());
  for (const double f : force->values) EXPECT_DOUBLE_EQ(f, 12000.0);
  const auto* temp = rec.find("temp_C");
  ASSERT_NE(temp, nullptr);
  EXPECT_NEAR(temp->values.front(), 50.0, 0.5);
  const std::string stored = io::read_run_attribute((dir / "out.h5").string(), "scenario");
  EXPECT_THAT(stored, HasSubstr("normal_force_N = 12000"));
  EXPECT_THAT(stored, Not(HasSubstr("25300")));
}

// A network takes the same keys as `sweep --set` on it, and --profile prints the simulation's
// wall time on a network as on the other kinds.
TEST(CliRunOptions, SetAndProfileWorkOnANetwork) {
  const auto dir = scratch_dir("run_set_network");
  const auto r = run_cli("run '" + source_path("scenarios/networks/lockup_clutch_controlled_slip.toml") +
                             "' -o out.h5 --set network.lockup_clutch.max_force_N=2600 --profile",
                         dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(io::read_run_attribute((dir / "out.h5").string(), "scenario"), HasSubstr("max_force_N = 2600"));
  EXPECT_THAT(r.out, HasSubstr("Profile: simulation wall time "));
}

// A misspelt key is the sweep's message: one line naming the key and the nearest allowed name.
TEST(CliRunOptions, MisspeltSetKeyNamesTheNearestKey) {
  const auto dir = scratch_dir("run_set_misspelt");
  const auto r = run_cli("run " + case1() + " -o out.h5 --set drive.normal_force=12000", dir);
  expect_rejected(r, {"shudder: error: ", "key 'drive.normal_force': unknown key; did you mean 'normal_force_N'?"});
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

// A range, a list, a non-number and a key given twice are refused with the form a run takes.
TEST(CliRunOptions, SetTakesOneNumberPerKey) {
  const auto dir = scratch_dir("run_set_values");
  expect_rejected(run_cli("run " + case1() + " -o out.h5 --set drive.normal_force_N=1000:3000:1000", dir),
                  {"--set", "a run takes one value per key", "expected KEY=VALUE"});
  expect_rejected(run_cli("run " + case1() + " -o out.h5 --set drive.normal_force_N=1000,2000", dir),
                  {"a run takes one value per key"});
  expect_rejected(run_cli("run " + case1() + " -o out.h5 --set drive.normal_force_N=heavy", dir),
                  {"'heavy' is not a finite number", "expected KEY=VALUE"});
  expect_rejected(
      run_cli("run " + case1() + " -o out.h5 --set drive.normal_force_N=1 --set drive.normal_force_N=2", dir),
      {"drive.normal_force_N", "given twice"});
  expect_rejected(run_cli("run " + case1() + " -o out.h5 --set scenario.name=1", dir),
                  {"scenario.name", "only numeric keys"});
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

// --sample-rate and --noise shape the measured run: without --measurement they would have no
// effect, so they are refused.
TEST(CliRunOptions, MeasuredRunOptionsWithoutMeasurementAreRefused) {
  const auto dir = scratch_dir("run_no_effect");
  expect_rejected(run_cli("run " + case1() + " -o out.h5 --sample-rate 100", dir),
                  {"shudder: error: --sample-rate applies to the measured run; give --measurement FILE.csv too"});
  expect_rejected(run_cli("run " + case1() + " -o out.h5 --noise", dir),
                  {"shudder: error: --noise applies to the measured run; give --measurement FILE.csv too"});
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
  // With --measurement both act.
  const auto r = run_cli("run " + case1() + " -o out.h5 --measurement m.csv --sample-rate 10 --noise", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Stick-slip beside linear theory's prediction: the summary says why "stable" there is no
// contradiction; a vibration verdict (a case that theory does see) gets no such line.
TEST(CliRunOptions, StickSlipSummarySaysLinearTheoryCannotPredictIt) {
  const auto dir = scratch_dir("run_stick_slip_note");
  const auto r = run_cli("run '" + source_path("scenarios/rig_stick_slip.toml") + "' -o s.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Shudder: stick_slip at"));
  EXPECT_THAT(r.out, HasSubstr("Predicted there: "));
  EXPECT_THAT(r.out, HasSubstr("Note: linear theory about the slipping point cannot predict stick-slip"));
  const auto v = run_cli("run '" + source_path("scenarios/paper_g_case1_25kN.toml") + "' -o c.h5", dir);
  ASSERT_EQ(v.exit_code, 0) << v.err;
  EXPECT_THAT(v.out, Not(HasSubstr("cannot predict stick-slip")));
}
