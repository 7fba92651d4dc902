// `shudder run --fixed-step` (docs/realtime.md): the run file carries the step, refusals are
// one-line input errors (exit 2).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "io/hdf5_run.hpp"
#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;

namespace {

TEST(CliFixedStep, RunsAPrescribedSlipScenarioAndRecordsTheStep) {
  const auto dir = scratch_dir("fixed_step_run");
  write_file(dir / "case1.toml",
             replace(shipped_scenario_text("paper_g_case1_25kN.toml"), "duration_s = 10.0", "duration_s = 0.5"));
  const auto r = run_cli("run case1.toml -o rt.h5 --fixed-step 1e-4", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rec = shudder::io::read_run_hdf5((dir / "rt.h5").string());
  ASSERT_NE(rec.find_scalar("fixed_step_s"), nullptr);
  EXPECT_EQ(rec.find_scalar("fixed_step_s")->value, 1e-4);
  EXPECT_EQ(rec.find("time_s")->values.size(), 51u);  // 0.5 s at 100 Hz, both ends
}

TEST(CliFixedStep, RefusesAStepThatDoesNotDivideTheSampleIntervalAndTheDriveline) {
  const auto dir = scratch_dir("fixed_step_refusals");
  const auto rig = run_cli("run '" + source_path("scenarios/rig_case2_15kN_378Hz.toml") + "' -o x.h5 --fixed-step 3e-4", dir);
  EXPECT_EQ(rig.exit_code, 2);
  EXPECT_THAT(rig.err, HasSubstr("--fixed-step 0.0003 s: the sample interval 1 / output.sample_rate_Hz (0.001 s) must "
                                 "be a whole number of fixed steps; choose a step that divides it"));
  const auto car = run_cli("run '" + source_path("scenarios/driveline_tight_turn.toml") + "' -o x.h5 --fixed-step 1e-4", dir);
  EXPECT_EQ(car.exit_code, 2);
  EXPECT_THAT(car.err, HasSubstr("key '--fixed-step': the fixed-step real-time mode covers the prescribed-slip clutch "
                                 "and the rig, not the driveline"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5"));
}

}  // namespace
