// Model-form mismatch with a larger gap (the held-out set's independent simulator,
// with another oil-flow calibration, left a 3.2 °C RMS gap with nothing hidden). Here the "other
// simulator" is our own model with a deliberately different calibration and discretisation:
// oil flow e = 0.020 against the model's 0.016 (25 % more flow through the interface), 60 radial
// cells and a 2.5 ms thermal step against 20 and 10 ms, probe runs at 14 kN / 70 °C and
// 26 kN / 90 °C (100 Hz, sensor noise). Without a tolerance the diagnosis names stand-ins for the
// mismatch (thermocouple_offset and rig_heat_capacity, "partly explained").
//
// The tolerance is read as docs/diagnosis.md "Choosing a tolerance" tells users to, on runs the
// diagnosed ones are not: the same two runs made with seeds 41 and 42 (the tests diagnose seeds
// 91 and 92), diagnosed with nothing hidden and `--max-effects 0`; per channel the part of the
// final RMS beyond the noise, √(RMS² − σ²), from the JSON's channels[].final_rms and .noise:
//   torque_Nm   √(0.801² − 0.615²) = 0.51 N m
//   temp_C      √(2.989² − 0.354²) = 2.97 °C
//   ir_temp_C   √(3.071² − 0.753²) = 2.98 °C
//   (sump_temp_C 0.383 against 0.328 of noise: takes temp_C's, as the docs say)
// Seeds 61 and 62 give 0.53, 2.92 and 2.91: the tolerance moves 2-4 % from one seed pair to the
// next, while the verdict's margin is 10 % (J ≤ 1.1²), so the seeds diagnosed here are unseen ones.
#include <gtest/gtest.h>

#include "analysis/diagnosis.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/diagnosis_probe.hpp"
#include "tests/support/diagnosis_runs.hpp"

namespace shudder {
namespace {

using test::scratch_dir;

const char* const kOtherSimulator =
    "[solver]\nradial_cells = 60\nthermal_step_ms = 2.5\n"
    "[effects.interface_oil_cooling]\nenabled = true\ne = 0.020\n";

analysis::DiagnosisResult diagnose_other_simulator(const std::string& name, const std::string& hidden) {
  const auto dir = scratch_dir(name);
  const std::string data = std::string(kOtherSimulator) + hidden;
  const std::vector<std::filesystem::path> csvs = {
      test::make_measured_run(dir, "a", test::probe_scenario_text(data, 14000, 70), 91),
      test::make_measured_run(dir, "b", test::probe_scenario_text(data, 26000, 90), 92)};
  analysis::DiagnosisOptions o;
  o.jobs = 1;                                                                  // ctest runs the cases in parallel
  o.tolerance = {{"torque_Nm", 0.51}, {"temp_C", 2.97}, {"ir_temp_C", 2.98}};  // seeds 41/42, above
  return test::diagnose_measured(csvs, test::probe_scenario_text("", 14000, 70), "scenarios/diagnosis_probe.toml", o);
}

TEST(DiagnoseLargerModelFormGap, TheMismatchAloneNamesNothingWithinTheTolerance) {
  const auto r = diagnose_other_simulator("diag_form_gap", "");
  EXPECT_TRUE(r.missing_effects.empty()) << test::describe_diagnosis(r);
  EXPECT_EQ(r.verdict, analysis::DiagnosisVerdict::kExplained) << test::describe_diagnosis(r);
  // The gap is of the size the tolerance was read from on seeds 41/42 (2.99 °C): 2-4 °C, as the
  // independent simulator left.
  EXPECT_GT(r.final.temp_rms_C, 2.0);
  EXPECT_LT(r.final.temp_rms_C, 4.0);
}

TEST(DiagnoseLargerModelFormGap, ABearingDragOnTopIsStillNamed) {
  // The thesis' μ = 0.005 adds μ·F·r ≈ 2.3-4.3 N m at 14 and 26 kN, several times the 0.51 N m
  // torque tolerance.
  const auto r =
      diagnose_other_simulator("diag_form_gap_drag", "[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.005\n");
  EXPECT_EQ(r.missing_effects, std::vector<std::string>{"bearing_drag"}) << test::describe_diagnosis(r);
  ASSERT_FALSE(r.final_effects.empty());
  EXPECT_NEAR(r.final_effects[0].parameters[0].second / 0.005, 1.0, 0.2);  // the 20 % target
}

TEST(DiagnoseLargerModelFormGap, ASensorLagOnTopIsNamedThroughTheThermocoupleAgainstTheIrSpot) {
  // A 1 s thermocouple lag adds ~3.3 °C RMS to temp_C, little more than its 2.97 °C tolerance, and the
  // extra oil flow is a heat sink rig_heat_capacity imitates on both thermometers: judged per
  // channel, rig_heat_capacity 535 J/K was named instead. The thermocouple less the
  // IR spot (the temp_minus_ir_C channel a temperature tolerance adds, analysis/misfit.hpp)
  // cancels the oil-flow gap and keeps the lag at its noise scale: the lag alone is named.
  const auto r = diagnose_other_simulator("diag_form_gap_lag",
                                          "[effects.temperature_sensor_lag]\nenabled = true\ntime_constant_s = 1.0\n");
  EXPECT_EQ(r.missing_effects, std::vector<std::string>{"temperature_sensor_lag"}) << test::describe_diagnosis(r);
  ASSERT_FALSE(r.final_effects.empty());
  EXPECT_NEAR(r.final_effects[0].parameters[0].second, 1.0, 0.2);  // the 20 % target
  bool difference_compared = false;
  for (const auto& c : r.channels) difference_compared = difference_compared || c.signal == "temp_minus_ir_C";
  EXPECT_TRUE(difference_compared);
}

}  // namespace
}  // namespace shudder
