// The backward check's tie rule and its reporting (analysis/effect_selection.cpp), on a fake
// model whose answer is known and where two effects explain the same gap exactly:
//
//   baseline  torque = 50 N m, temp = 20 °C + 1 K/s · t   (one run, 10 s at 100 Hz)
//   sink      temp −= a · t              (1 parameter: heat carried away at a fixed rate)
//   store     temp −= b · t + c · t²     (2 parameters: its b·t is the sink's shape; b is signed,
//                                         fitted linearly, so the degenerate split a/b in a joint
//                                         fit stays interior wherever it lands)
//
// Hidden: sink a = 0.5 K/s and store b = 0.02 K/s, c = 0.01 K/s². The first round's gap is huge
// (J ≈ 10⁴), so the per-parameter price 0.02·s makes the one-parameter sink win round 1 although
// the store alone would fit everything; round 2 adds the store for the t² part. Taking the sink
// out then costs nothing (the store's b moves 0.02 → 0.52 and takes its share): the data cannot
// separate them. The tie rule keeps the sink (fewer parameters) and reports the pair.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"

namespace {

using shudder::analysis::DiagnosisOptions;
using shudder::analysis::DiagnosisResult;
using shudder::analysis::DiagnosisRun;
using shudder::analysis::EffectCandidate;
using shudder::analysis::EffectSetting;
using shudder::analysis::Prediction;

Prediction predict(const DiagnosisRun& run, const std::vector<EffectSetting>& added) {
  Prediction p;
  for (double t : run.time_s) {
    p.torque_Nm.push_back(50.0);
    double temp = 20.0 + 1.0 * t;
    for (const auto& e : added) {
      if (e.effect == "sink") temp -= e.values[0] * t;
      if (e.effect == "store") temp -= e.values[0] * t + e.values[1] * t * t;
    }
    p.temp_C.push_back(temp);
  }
  return p;
}

std::vector<EffectCandidate> candidates(double store_b_upper) {
  return {{"sink", "heat leaves at a fixed rate", {"a"}, {{0.1}, {1.0}}, {1e-3}, {10.0}, {}},
          {"store",
           "heat stored and given back",
           {"b", "c"},
           {{0.01, 0.005}, {0.1, 0.05}},
           {-1.0, 1e-4},
           {store_b_upper, 10.0},
           {true, false}}};
}

DiagnosisResult diagnose_pair(const DiagnosisOptions& o, double store_b_upper = 10.0) {
  DiagnosisRun run;
  run.name = "pair.csv";
  for (int i = 0; i <= 1000; ++i) {
    run.time_s.push_back(0.01 * i);
    run.speed_rpm.push_back(50.0);
    run.normal_force_N.push_back(10000.0);
  }
  const Prediction truth = predict(run, {{"sink", {0.5}}, {"store", {0.02, 0.01}}});
  std::mt19937 rng(5);
  std::normal_distribution<double> torque_noise(0.0, 0.05), temp_noise(0.0, 0.02);
  for (std::size_t i = 0; i < run.time_s.size(); ++i) {
    run.torque_Nm.push_back(truth.torque_Nm[i] + torque_noise(rng));
    run.temp_C.push_back(truth.temp_C[i] + temp_noise(rng));
  }
  const std::vector<DiagnosisRun> runs{run};
  const auto simulate = [&](const std::vector<EffectSetting>& added, std::size_t k) { return predict(runs[k], added); };
  return shudder::analysis::diagnose(runs, candidates(store_b_upper), simulate, o);
}

TEST(BackwardCheck, KeepsTheEffectWithFewerParametersWhenTheDataCannotSeparateThem) {
  const auto r = diagnose_pair(DiagnosisOptions{});
  ASSERT_EQ(r.missing_effects, (std::vector<std::string>{"sink", "store"}));
  EXPECT_TRUE(r.withdrawn.empty());
  ASSERT_EQ(r.indistinguishable.size(), 1u);
  const auto& f = r.indistinguishable[0];
  EXPECT_EQ(f.effect, "sink");
  EXPECT_EQ(f.stand_in, "store");
  EXPECT_FALSE(f.withdrawn);
  EXPECT_EQ(f.kept_because, "store could stand in but has more parameters");
  // The move the store makes: b from the hidden 0.02 towards a + b = 0.52.
  EXPECT_EQ(f.stand_in_move.rfind("b ", 0), 0u) << f.stand_in_move;
  // Exactly degenerate shapes: the store reproduces the sink to the refit's tolerance, far
  // below the 0.04 · s it would need (one parameter, s = 1 at the noise).
  EXPECT_LT(f.holdout_cost, f.needed_gain);
  EXPECT_NEAR(f.needed_gain, 0.04, 0.04 * 0.2);  // s = max(1, J) with J ≈ 1 (noise estimate ±10 %)
  // Only the sum a + b is identifiable (the split is the degenerate pair's): 0.52 to 2 %
  // (the slope of 1001 samples over 10 s at σ = 0.02 K is known to ~1e-4 K/s).
  ASSERT_EQ(r.final_effects.size(), 2u);
  EXPECT_NEAR((r.final_effects[0].parameters[0].second + r.final_effects[1].parameters[0].second) / 0.52, 1.0, 0.02);
}

TEST(BackwardCheck, WithoutTheStandInRuleTheRedundantEffectIsWithdrawnAndReported) {
  // A stand-in threshold no move reaches: the sink is expendable and nothing else keeps it, so
  // it is withdrawn (the check before the tie rule did this), reported with its cost.
  DiagnosisOptions o;
  o.stand_in_shift = 1e9;
  const auto r = diagnose_pair(o);
  EXPECT_EQ(r.missing_effects, std::vector<std::string>{"store"});
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].effect, "store");
  ASSERT_EQ(r.withdrawn.size(), 1u);
  EXPECT_EQ(r.withdrawn[0].effect, "sink");
  EXPECT_TRUE(r.withdrawn[0].withdrawn);
  EXPECT_LT(r.withdrawn[0].holdout_cost, r.withdrawn[0].needed_gain);
  EXPECT_TRUE(r.indistinguishable.empty());
  // The store alone takes the sum: b = a + b_hidden = 0.52 (±5 %: the fit's split is gone).
  ASSERT_EQ(r.final_effects.size(), 1u);
  EXPECT_NEAR(r.final_effects[0].parameters[0].second / 0.52, 1.0, 0.05);
}

TEST(BackwardCheck, NeverWithdrawsInFavourOfAnEffectPushedToABound) {
  // The store's b may not exceed 0.53: standing in for the sink (b → 0.52) puts it within
  // bound_margin of its bound, so the sink stays even with the stand-in rule off.
  DiagnosisOptions o;
  o.stand_in_shift = 1e9;
  const auto r = diagnose_pair(o, 0.53);
  ASSERT_EQ(r.missing_effects, (std::vector<std::string>{"sink", "store"}));
  EXPECT_TRUE(r.withdrawn.empty());
  ASSERT_EQ(r.indistinguishable.size(), 1u);
  EXPECT_EQ(r.indistinguishable[0].effect, "sink");
  EXPECT_EQ(r.indistinguishable[0].kept_because, "without it store's b goes to its bound");
}

}  // namespace
