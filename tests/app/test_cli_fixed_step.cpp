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

TEST(CliFixedStep, RunsANetworkOnTheSameEquationsAsTheAdaptiveRun) {
  // The wet-clutch bench network (negative-slope fluid: the housing judders at the bar's
  // 378 Hz). Both runs judge the same vibration; the frequency is the bar's, which RK4 at
  // h = 50 µs (ωh = 0.12) reproduces to (ωh)⁴/24 = 1e-5 of it: bound 0.5 % for the FFT's bin.
  const auto dir = scratch_dir("fixed_step_network");
  std::string fluids = source_path("scenarios/fluids");
  fluids.insert(0, 1, '"');
  fluids += '/';
  write_file(dir / "bench.toml", replace(replace(slurp(source_path("scenarios/networks/wet_clutch_bench.toml")),
                                                 "duration_s = 2.0", "duration_s = 1.0"),
                                         "\"../fluids/", fluids));
  const auto ad = run_cli("run bench.toml -o ad.h5", dir);
  const auto rt = run_cli("run bench.toml -o rt.h5 --fixed-step 5e-5", dir);
  ASSERT_EQ(ad.exit_code, 0) << ad.err;
  ASSERT_EQ(rt.exit_code, 0) << rt.err;
  const auto a = shudder::io::read_run_hdf5((dir / "ad.h5").string());
  const auto b = shudder::io::read_run_hdf5((dir / "rt.h5").string());
  ASSERT_NE(b.find_scalar("fixed_step_s"), nullptr);
  EXPECT_EQ(b.find_scalar("fixed_step_s")->value, 5e-5);
  EXPECT_EQ(b.find_scalar("integrator_steps")->value, 20000.0);
  EXPECT_EQ(a.find("time_s")->values.size(), b.find("time_s")->values.size());
  const auto* va = a.find_block("verdict");
  const auto* vb = b.find_block("verdict");
  ASSERT_TRUE(va && vb);
  EXPECT_EQ(va->find_text("verdict")->value, vb->find_text("verdict")->value);
  if (const auto* fa = va->find_scalar("frequency_Hz")) {
    EXPECT_NEAR(vb->find_scalar("frequency_Hz")->value, fa->value, 5e-3 * fa->value);
  }
}

TEST(CliFixedStep, RefusesAStepThatDoesNotDivideTheSampleIntervalOrTheThermalStep) {
  const auto dir = scratch_dir("fixed_step_refusals");
  const auto rig =
      run_cli("run '" + source_path("scenarios/rig_case2_15kN_378Hz.toml") + "' -o x.h5 --fixed-step 3e-4", dir);
  EXPECT_EQ(rig.exit_code, 2);
  EXPECT_THAT(rig.err, HasSubstr("--fixed-step 0.0003 s: the thermal step solver.thermal_step_ms (0.01 s) must be a "
                                 "whole number of fixed steps; choose a step that divides it"));
  const auto car =
      run_cli("run '" + source_path("scenarios/driveline_tight_turn.toml") + "' -o x.h5 --fixed-step 2e-3", dir);
  EXPECT_EQ(car.exit_code, 2);
  EXPECT_THAT(car.err,
              HasSubstr("--fixed-step 0.002 s: the sample interval 1 / output.sample_rate_Hz (0.001 s) must be "
                        "a whole number of fixed steps"));
  const auto net =
      run_cli("run '" + source_path("scenarios/networks/wet_clutch_bench.toml") + "' -o x.h5 --fixed-step 2e-4", dir);
  EXPECT_EQ(net.exit_code, 2);
  EXPECT_THAT(net.err,
              HasSubstr("key 'output.sample_rate_Hz': --fixed-step 0.0002 s: the sample interval (5e-05 s) must be "
                        "a whole number of fixed steps"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5"));
}

}  // namespace
