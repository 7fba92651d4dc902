// `shudder sweep` end to end: the /cases table (one dataset per swept key and per result, equal
// lengths), prediction and simulation agreeing on a case that shudders, resuming an interrupted
// sweep, and bad --set arguments.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "io/hdf5_sweep.hpp"
#include "tests/support/cli.hpp"

using namespace shudder;
using namespace shudder::test;
using ::testing::HasSubstr;

namespace {

// The negative-slope rig case, shortened to 0.4 s (the clutch-side mode grows at ~13 1/s from
// the start, so the oscillation is clear well before).
std::string short_shudder_scenario() {
  std::string s = slurp(source_path("scenarios/rig_shudder_negative_slope.toml"));
  const auto replace = [&s](const std::string& from, const std::string& to) {
    const auto pos = s.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    s.replace(pos, from.size(), to);
  };
  replace("duration_s = 2.0", "duration_s = 0.4");
  replace("time_s = [0.0, 2.0]", "time_s = [0.0, 0.4]");
  replace("fluids/schematic_negative_slope.toml", source_path("scenarios/fluids/schematic_negative_slope.toml"));
  replace("sample_rate_Hz = 20000.0", "sample_rate_Hz = 10000.0");
  return s;
}

const char* kKey = "rig.torsion_bar.natural_frequency_Hz";

}  // namespace

TEST(CliSweep, CasesTableHasOneRowPerCaseAndPredictionMatchesTheShudder) {
  const auto dir = scratch_dir("sweep_table");
  write_file(dir / "s.toml", short_shudder_scenario());
  const auto r = run_cli(std::string("sweep s.toml --set ") + kKey + "=200:400:100 --jobs 2 -o sw.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "sw.h5.parts"));  // removed once complete
  const io::SweepTable t = io::read_sweep_table((dir / "sw.h5").string());
  const auto* key = t.find(kKey);
  ASSERT_NE(key, nullptr);
  EXPECT_THAT(key->values, ::testing::ElementsAre(200.0, 300.0, 400.0));
  for (const char* col : {"predicted_stable", "predicted_margin_per_s", "predicted_frequency_Hz",
                          "simulated_frequency_Hz", "amplitude_Nm", "onset_time_s"}) {
    const auto* c = t.find(col);
    ASSERT_NE(c, nullptr) << col;
    EXPECT_EQ(c->values.size(), 3u) << col;
  }
  ASSERT_EQ(t.text_column_name, "simulated_verdict");
  ASSERT_EQ(t.text_column.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    // The slope (-1.5 N m s/rad) beats the bar damping (2ζ√(kJ) = 0.50–1.0 N m s/rad) on all
    // three bars: predicted unstable, and the run vibrates.
    EXPECT_EQ(t.find("predicted_stable")->values[k], 0.0);
    EXPECT_EQ(t.text_column[k], "vibration");
    // The housing mode is decoupled by the slipping clutch: the predicted frequency is the
    // bar's damped frequency (within its small damping shift, < 1 %), and the simulated one
    // agrees within 2 % (issue 4's prediction target).
    const double f = key->values[k];
    EXPECT_NEAR(t.find("predicted_frequency_Hz")->values[k], f, 0.01 * f);
    EXPECT_NEAR(t.find("simulated_frequency_Hz")->values[k], t.find("predicted_frequency_Hz")->values[k], 0.02 * f);
  }
}

TEST(CliSweep, InterruptedSweepResumesWithFinishedCasesKept) {
  const auto dir = scratch_dir("sweep_resume");
  write_file(dir / "s.toml", short_shudder_scenario());
  // A first sweep over two values leaves its parts (as an interrupted run would) ...
  auto r = run_cli(std::string("sweep s.toml --set ") + kKey + "=200,300 --jobs 1 --keep-parts -o sw.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto first = io::read_sweep_table((dir / "sw.h5").string());
  // ... the extended sweep reuses both and runs only the new case.
  r = run_cli(std::string("sweep s.toml --set ") + kKey + "=200,300,400 --jobs 1 -o sw.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("resuming: 2 of 3 cases already finished"));
  EXPECT_THAT(r.out, HasSubstr("(1 run now"));
  const auto second = io::read_sweep_table((dir / "sw.h5").string());
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_EQ(second.find("amplitude_Nm")->values[k], first.find("amplitude_Nm")->values[k]);
}

TEST(CliSweep, BadSetArgumentsExitTwoNamingTheProblem) {
  const auto dir = scratch_dir("sweep_bad");
  write_file(dir / "s.toml", short_shudder_scenario());
  struct Case { std::string set, fragment; };
  for (const auto& c : std::vector<Case>{
           {std::string(kKey) + "=400:200:100", "STOP >= START"},
           {std::string(kKey) + "=100:200:0", "STEP must be > 0"},
           {std::string(kKey) + "=abc", "not a finite number"},
           {"rig.torsion_bar.natural_frequency_Hzz=100,200", "unknown key"},
           {std::string(kKey) + "=0.5,200", "[1, 10000]"}}) {
    const auto r = run_cli("sweep s.toml --set '" + c.set + "' -o sw.h5", dir);
    EXPECT_EQ(r.exit_code, 2) << c.set << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.fragment)) << c.set;
    EXPECT_FALSE(std::filesystem::exists(dir / "sw.h5")) << c.set;
  }
}
