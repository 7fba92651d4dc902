// What the diagnosis' fits simulate, counted per run on a fake model (tests/support/
// switch_pair_diagnosis.hpp, with an "idle" switch added; analysis/joint_step.hpp
// "Cost", analysis/candidate_fit.hpp): the counts follow from the fits' own `evaluations`
// (each one simulation of every fit run, counted alike for single and joint candidates) in
// closed form, so every simulation is accounted for.
//
//   three runs at "load" L = 10, 25 (fit) and 15 (held out), 5 s at 100 Hz
//   baseline   torque = 100 N m, temp = 20 °C + 1 K/s · t
//   warm, load switches (friction following the temperature rise, falling with the load);
//   idle       a switch that changes nothing; gain: torque × g (one parameter)
//   measured   warm and load on, torque × 1.01, with noise
//
//   single candidate:  each fit run evaluations times, the hold-out run once (at the fitted values);
//                      a switch with nothing to fit: 0 evaluations, every run once
//   joint step:        each fit run pairs + evaluations times (the screen, then the fit,
//                      which starts from the chosen pair's screen), the hold-out run once
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <string>
#include <vector>

#include "analysis/candidate_fit.hpp"
#include "analysis/joint_step.hpp"
#include "analysis/misfit.hpp"
#include "tests/support/switch_pair_diagnosis.hpp"

namespace shudder::analysis {
namespace {

Prediction predict(const DiagnosisRun& run, const std::vector<EffectSetting>& added) {
  return test::switch_pair_prediction(run, added);
}

// Warm and load on, the torque cell 1 % high.
std::vector<DiagnosisRun> measured_runs() {
  return test::switch_pair_runs({{"warm", {}}, {"load", {}}, {"gain", {1.01}}}, 500, 11);
}

std::vector<EffectCandidate> candidates() {
  std::vector<EffectCandidate> c = test::switch_pair_candidates();
  c.push_back({"idle", "changes nothing", {}, {}, {}, {}, {}});
  return c;
}

struct Counted {
  std::vector<DiagnosisRun> runs = measured_runs();
  std::vector<EffectCandidate> cands = candidates();
  DiagnosisOptions opt;
  MisfitModel misfit{runs, opt};
  std::array<std::atomic<int>, 3> count{};
  Simulator sim = [this](const std::vector<EffectSetting>& added, std::size_t k) {
    ++count.at(k);
    return predict(runs[k], added);
  };
  CandidateFitter fitter{runs, cands, sim, misfit, opt};

  Predictions uncounted(const Config& config) const {
    Predictions p(runs.size());
    for (std::size_t k = 0; k < runs.size(); ++k) p[k] = predict(runs[k], config);
    return p;
  }
  void reset() {
    for (auto& c : count) c = 0;
  }
};

TEST(DiagnosisCost, TheSplitHoldsOutTheLastRun) {
  Counted c;
  ASSERT_EQ(c.misfit.holdout_split().kind, HoldoutSplit::Kind::kLastRun);  // the closed forms below assume it
  EXPECT_EQ(c.misfit.fit().runs(), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(c.misfit.holdout().runs(), std::vector<std::size_t>{2});
}

TEST(DiagnosisCost, ASingleCandidateSimulatesEachFitRunOncePerEvaluationAndTheHoldOutOnce) {
  Counted c;
  const CandidateOutcome o = c.fitter.fit_candidate(c.cands[0], {}, c.uncounted({}));
  ASSERT_TRUE(o.ok) << o.score.failure;
  ASSERT_GT(o.score.evaluations, 1);
  EXPECT_EQ(c.count[0], o.score.evaluations);
  EXPECT_EQ(c.count[1], o.score.evaluations);
  EXPECT_EQ(c.count[2], 1);
}

TEST(DiagnosisCost, ASwitchWithNothingToFitCountsNoEvaluationsAndSimulatesEachRunOnce) {
  Counted c;
  const CandidateOutcome o = c.fitter.fit_candidate(c.cands[1], {}, c.uncounted({}));
  ASSERT_TRUE(o.ok) << o.score.failure;
  EXPECT_EQ(o.score.evaluations, 0);
  EXPECT_EQ(c.count[0], 1);
  EXPECT_EQ(c.count[1], 1);
  EXPECT_EQ(c.count[2], 1);
}

TEST(DiagnosisCost, TheJointScreenSimulatesOnlyTheFitRuns) {
  Counted c;
  // The gain already added (its parameter is refitted with the pair, so the fit evaluates more
  // than once); the three open switches make three pairs, no single candidate is paired.
  const Config fold{{"gain", {1.0}}};
  const std::vector<const EffectCandidate*> open{&c.cands[1], &c.cands[2], &c.cands[3]};
  const auto pair = joint_candidate(open, {}, fold, c.uncounted(fold), c.fitter, c.misfit, c.opt);
  ASSERT_TRUE(pair && pair->ok);
  EXPECT_EQ(pair->score.effect, "warm");  // the pair that closes the gap ranks first
  EXPECT_EQ(pair->score.joint_with, std::vector<std::string>{"load"});
  const int pairs = 3, evaluations = pair->score.evaluations;
  ASSERT_GT(evaluations, 1);
  EXPECT_EQ(c.count[0], pairs + evaluations);
  EXPECT_EQ(c.count[1], pairs + evaluations);
  EXPECT_EQ(c.count[2], 1);  // the chosen pair's hold-out, at its fitted values; no pair's screen
}

TEST(DiagnosisCost, APairOfSwitchesAloneIsNotFittedOnlyScreened) {
  Counted c;
  // Nothing added: the pairs have no parameters, so the chosen one is its screen (0 evaluations).
  const std::vector<const EffectCandidate*> open{&c.cands[1], &c.cands[2], &c.cands[3]};
  const auto pair = joint_candidate(open, {}, {}, c.uncounted({}), c.fitter, c.misfit, c.opt);
  ASSERT_TRUE(pair && pair->ok);
  EXPECT_EQ(pair->score.evaluations, 0);
  EXPECT_EQ(c.count[0], 3);
  EXPECT_EQ(c.count[1], 3);
  EXPECT_EQ(c.count[2], 1);
}

}  // namespace
}  // namespace shudder::analysis
