// The joint step (analysis/joint_step.hpp) on the probe's runs, built like the every-effect-off
// Case 2 benchmark in a fast configuration: three runs at 10.4 and 25.3 kN (fit) and 14.8 kN
// (held out, between the others) from 80 °C, the 20 s probe cycle at 100 Hz with sensor noise.
// The diagnosis model has both friction switches off (temperature- and load-dependent
// friction). Without the joint step the search names a 1.9 % load-cell gain and stops "partly
// explained" (torque 4.3 × its scale): each switch alone is worse on the held-out run than the
// gain (J 1.45 and 3.08 against 1.14), and after the gain neither alone helps (2.03, 1.59).
#include <gtest/gtest.h>

#include <algorithm>

#include "analysis/diagnosis.hpp"
#include "report/diagnosis_narrative.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/diagnosis_probe.hpp"
#include "tests/support/diagnosis_runs.hpp"

namespace shudder {
namespace {

using test::scratch_dir;
using Names = std::vector<std::string>;

std::string probe(const std::string& extra, double force_N) { return test::probe_scenario_text(extra, force_N, 80.0); }

std::string off(const std::string& effect) { return "[effects." + effect + "]\nenabled = false\n"; }
const std::string kSwitchesOff = off("temperature_dependent_friction") + off("load_dependent_friction");

analysis::DiagnosisResult diagnose_three_loads(const std::string& name, const std::string& hidden) {
  const auto dir = scratch_dir("diag_joint_" + name);
  std::vector<std::filesystem::path> csvs;
  const struct {
    double force;
    unsigned seed;
  } spec[] = {{10400, 31}, {25300, 32}, {14800, 33}};  // last held out
  for (const auto& r : spec)
    csvs.push_back(test::make_measured_run(dir, "run_" + std::to_string(static_cast<int>(r.force)),
                                           probe(hidden, r.force), r.seed));
  analysis::DiagnosisOptions o;
  o.jobs = 1;  // ctest runs the cases in parallel
  return test::diagnose_measured(csvs, probe(kSwitchesOff, 14800), "scenarios/diagnosis_probe.toml", o);
}

Names sorted(Names v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(DiagnoseJointStep, BothFrictionSwitchesHiddenAreNamedTogether) {
  const auto r = diagnose_three_loads("both", "");
  EXPECT_EQ(sorted(r.missing_effects), sorted({"temperature_dependent_friction", "load_dependent_friction"}))
      << test::describe_diagnosis(r);
  // Added in one joint step (one step for two effects).
  ASSERT_EQ(r.steps.size(), 1u) << test::describe_diagnosis(r);
  EXPECT_EQ(r.steps[0].joint_with.size(), 1u);
  EXPECT_EQ(r.verdict, analysis::DiagnosisVerdict::kExplained) << test::describe_diagnosis(r);
}

TEST(DiagnoseJointStep, OneSwitchHiddenIsNamedWithoutAPartner) {
  // Only temperature-dependent friction in the data (its load dependence off there too).
  const auto r = diagnose_three_loads("temperature_only", off("load_dependent_friction"));
  EXPECT_EQ(r.missing_effects, Names{"temperature_dependent_friction"}) << test::describe_diagnosis(r);
}

TEST(DiagnoseJointStep, WhereThePairDoesNotHelpNeitherSwitchIsNamed) {
  // Both switches off in the data as in the model, a 5 % low load cell hidden: the pair's
  // friction changes are not in the data, the gain is.
  const auto r =
      diagnose_three_loads("load_gain", kSwitchesOff + "[effects.load_sensor_gain]\nenabled = true\ngain = 0.95\n");
  EXPECT_EQ(r.missing_effects, Names{"load_sensor_gain"}) << test::describe_diagnosis(r);
}

}  // namespace
}  // namespace shudder
