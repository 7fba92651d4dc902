// Named only when found (analysis/explanation_check.hpp), on the linear problem of
// tests/support/linear_diagnosis.hpp (torque = 50 N m + a·speed, temp = 20 °C + 0.1 K/s·t + b·t;
// a, b in [1e-3, 10]; noise 0.05 N m, 0.02 K):
//   * a parameter within 2 % of its log range from a bound (a factor 10^(4·0.02) = 1.20) is
//     "pulled to its bound", with the likely cause of its effect where known;
//   * a gap left above 1.1 × the error scale without a tolerance, above 2 × with one, leaves
//     every added effect not named;
//   * end to end: a torque that grows with speed² is half explained by a slope; without a
//     tolerance the slope is not named and the verdict says why.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/candidate_fit.hpp"
#include "analysis/explanation_check.hpp"
#include "analysis/misfit.hpp"
#include "tests/support/linear_diagnosis.hpp"

namespace shudder::analysis {
namespace {

using ::testing::HasSubstr;

struct Fixture {
  std::vector<DiagnosisRun> runs{test::linear_measured_run({{"torque_slope", {0.3}}})};
  std::vector<EffectCandidate> candidates = test::linear_candidates();
  Simulator sim = [this](const std::vector<EffectSetting>& added, std::size_t k) {
    return test::linear_prediction(runs[k], added);
  };
  DiagnosisOptions opt;
  MisfitModel misfit{runs, opt};
  CandidateFitter fitter{runs, candidates, sim, misfit, opt};
};

ChannelFit channel(double final_misfit) {
  ChannelFit c;
  c.signal = "torque_Nm";
  c.final_misfit = final_misfit;
  return c;
}

TEST(ExplanationCheck, AParameterAtItsBoundIsNotFound) {
  Fixture f;
  // 8.5 is within a factor 1.20 of the upper bound 10; 7.9 is not.
  const auto at = unexplained_effects({{"torque_slope", {8.5}}}, f.fitter, {channel(1.0)}, f.opt);
  ASSERT_EQ(at.size(), 1u);
  EXPECT_EQ(at[0].parameter, "slope_Nm_per_rpm");
  EXPECT_EQ(at[0].bound, 10.0);
  EXPECT_THAT(at[0].reason, HasSubstr("the data pull torque_slope's slope_Nm_per_rpm to its bound 10"));
  EXPECT_TRUE(unexplained_effects({{"torque_slope", {7.9}}}, f.fitter, {channel(1.0)}, f.opt).empty());
  // Fitted with it, the other effect is not named either.
  const auto both =
      unexplained_effects({{"extra_heating", {0.5}}, {"torque_slope", {1.1e-3}}}, f.fitter, {channel(1.0)}, f.opt);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_THAT(both[0].reason, HasSubstr("fitted together with an effect the data pull to its bound"));
  EXPECT_EQ(both[1].bound, 1e-3);
}

TEST(ExplanationCheck, AGapLeftAboveTheScaleLeavesTheEffectsNotNamed) {
  Fixture f;
  const Config slope{{"torque_slope", {0.3}}};
  // Without a tolerance: the verdict's 1.1 (J 1.21) is the limit.
  EXPECT_TRUE(unexplained_effects(slope, f.fitter, {channel(1.2)}, f.opt).empty());
  const auto gap = unexplained_effects(slope, f.fitter, {channel(1.3)}, f.opt);
  ASSERT_EQ(gap.size(), 1u);
  EXPECT_THAT(gap[0].reason, HasSubstr("torque_Nm gap stays at 1.14x its error scale"));
  EXPECT_THAT(gap[0].likely_cause, HasSubstr("no --tolerance given"));
  // With a tolerance: 2 × (J 4).
  f.opt.tolerance = {{"torque_Nm", 0.1}};
  EXPECT_TRUE(unexplained_effects(slope, f.fitter, {channel(3.9)}, f.opt).empty());
  EXPECT_EQ(unexplained_effects(slope, f.fitter, {channel(4.1)}, f.opt).size(), 1u);
}

TEST(ExplanationCheck, LikelyCausesNameTheFrictionLawOrTheThermalModel) {
  EXPECT_THAT(likely_cause_at_bound("torque_sensor_gain"), HasSubstr("another friction radius"));
  EXPECT_THAT(likely_cause_at_bound("sump_heating"), HasSubstr("thermal model's form"));
  EXPECT_EQ(likely_cause_at_bound("torque_slope"), "");
}

TEST(ExplanationCheck, AHalfExplainedGapNamesNothingWithoutATolerance) {
  // Measured: 50 + 0.3·speed + 0.004·speed² (up to +40 N m at 100 rpm): the slope closes most of
  // it, the curvature (~5 N m, 100 σ) stays.
  auto run = test::linear_measured_run({{"torque_slope", {0.3}}});
  for (std::size_t i = 0; i < run.time_s.size(); ++i) run.torque_Nm[i] += 0.004 * run.speed_rpm[i] * run.speed_rpm[i];
  const std::vector<DiagnosisRun> runs{run};
  const Simulator sim = [&](const std::vector<EffectSetting>& added, std::size_t k) {
    return test::linear_prediction(runs[k], added);
  };
  const DiagnosisResult r = diagnose(runs, test::linear_candidates(), sim, {});
  EXPECT_TRUE(r.missing_effects.empty());
  EXPECT_TRUE(r.final_effects.empty());
  EXPECT_EQ(r.verdict, DiagnosisVerdict::kNotExplained);
  ASSERT_FALSE(r.not_explained.empty());
  EXPECT_EQ(r.not_explained[0].effect, "torque_slope");
  EXPECT_THAT(r.not_explained[0].likely_cause, HasSubstr("no --tolerance given"));
  // The final model is the baseline.
  EXPECT_DOUBLE_EQ(r.final.torque_rms_Nm, r.baseline.torque_rms_Nm);
}

}  // namespace
}  // namespace shudder::analysis
