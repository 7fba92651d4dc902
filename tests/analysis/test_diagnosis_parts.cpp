// The diagnosis' parts on problems with known answers (fast: each well under a second):
//   noise estimate   analysis/noise_estimate against white noise of known sigma;
//   log-parameter fit analysis/log_parameter_fit recovering the parameters of a closed form;
//   diagnose         with the linear fake model of tests/support/linear_diagnosis.hpp;
//   misfit           the thermocouple-against-IR channel (analysis/misfit.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "analysis/log_parameter_fit.hpp"
#include "analysis/misfit.hpp"
#include "analysis/noise_estimate.hpp"
#include "tests/support/linear_diagnosis.hpp"

namespace {

using shudder::analysis::DiagnosisOptions;
using shudder::analysis::DiagnosisRun;
using shudder::analysis::EffectSetting;
using shudder::analysis::estimate_noise_sigma;

std::vector<double> white_noise(std::size_t n, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> d(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = d(rng);
  return x;
}

// Sampling error of the estimator: 1.4826·MAD has a relative standard error of ≈ 1.17/√n for
// Gaussian data (MAD's 37 % efficiency); the second differences are correlated (lag 1: −2/3,
// lag 2: 1/6), which at most doubles that. n = 20000: ≈ 1.7 % at 2 standard errors of the
// doubled value, so 4 % relative is > 4 standard errors yet tight enough to catch a wrong
// constant (a missing √6 is a factor 2.4, a plain MAD of x a bias of ~0).
constexpr std::size_t kNoiseSamples = 20000;
constexpr double kNoiseRelTol = 0.04;

TEST(NoiseEstimate, RecoversTheSigmaOfSeededWhiteNoise) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const double sigma = 0.3;
    EXPECT_NEAR(estimate_noise_sigma(white_noise(kNoiseSamples, sigma, seed)) / sigma, 1.0, kNoiseRelTol)
        << "seed " << seed;
  }
}

TEST(NoiseEstimate, ASmoothSignalAddsAlmostNothing) {
  // 1 Hz sine of amplitude 10 at 1 kHz: its second difference is at most (2π f)² A dt² =
  // 3.9e-4, so alone it reads as < 3.9e-4 / √6 · 1.4826 ≈ 2.4e-4; with noise of 0.3 on top the
  // estimate moves by far less than the sampling tolerance.
  const double dt = 1e-3, amplitude = 10.0, f = 1.0;
  std::vector<double> smooth(kNoiseSamples);
  for (std::size_t i = 0; i < smooth.size(); ++i)
    smooth[i] = amplitude * std::sin(2.0 * std::numbers::pi * f * dt * static_cast<double>(i));
  const double bound = std::pow(2.0 * std::numbers::pi * f, 2) * amplitude * dt * dt * 1.4826 / std::sqrt(6.0);
  EXPECT_LT(estimate_noise_sigma(smooth), bound);
  const auto noise = white_noise(kNoiseSamples, 0.3, 4);
  std::vector<double> both(kNoiseSamples);
  for (std::size_t i = 0; i < both.size(); ++i) both[i] = smooth[i] + noise[i];
  EXPECT_NEAR(estimate_noise_sigma(both) / estimate_noise_sigma(noise), 1.0, 1e-2);
}

TEST(NoiseEstimate, PoolingWeighsEachRunBySampleCountAndKeepsTheFloor) {
  const auto a = white_noise(3000, 0.2, 5), b = white_noise(1000, 0.6, 6);
  const double sa = estimate_noise_sigma(a), sb = estimate_noise_sigma(b);
  const double expected = std::sqrt((3000.0 * sa * sa + 1000.0 * sb * sb) / 4000.0);
  EXPECT_NEAR(shudder::analysis::pooled_noise_sigma({&a, &b}, 0.0), expected, 1e-14 * expected);
  const std::vector<double> flat(100, 1.0);
  EXPECT_EQ(shudder::analysis::pooled_noise_sigma({&flat}, 1e-3), 1e-3);
}

TEST(LogParameterFit, RecoversTheParametersOfADecay) {
  // y(t) = A exp(−t / τ) on 50 points, no noise: the least-squares minimum is the truth with
  // zero cost. LM stops on MINPACK's relative tolerances (~1e-8 of the cost), so the values
  // are recovered to ≪ 1e-4 relative, the tolerance.
  const double A = 3.0, tau = 0.7;
  std::vector<double> t, y;
  for (int i = 0; i < 50; ++i) {
    t.push_back(0.05 * i);
    y.push_back(A * std::exp(-t.back() / tau));
  }
  shudder::analysis::LogParameterProblem problem;
  problem.residuals = static_cast<int>(t.size());
  problem.lower = {1e-3, 1e-3};
  problem.upper = {1e3, 1e3};
  problem.starts = {{10.0, 0.1}, {1.0, 1.0}};
  problem.max_evaluations = 400;
  problem.evaluate = [&](const std::vector<double>& v, Eigen::VectorXd& r) {
    r.resize(static_cast<Eigen::Index>(t.size()));
    for (std::size_t i = 0; i < t.size(); ++i) r[static_cast<Eigen::Index>(i)] = v[0] * std::exp(-t[i] / v[1]) - y[i];
    return true;
  };
  const auto fit = shudder::analysis::fit_log_parameters(problem);
  ASSERT_TRUE(fit.feasible);
  EXPECT_NEAR(fit.values[0] / A, 1.0, 1e-4);
  EXPECT_NEAR(fit.values[1] / tau, 1.0, 1e-4);
  EXPECT_LT(fit.cost, 1e-10);
  EXPECT_LE(fit.evaluations, problem.max_evaluations);
}

// A signed parameter (a sensor offset) marked linear: y = A exp(-t/tau) + c with c = -3 is
// found exactly (noise-free data), from a start of the other sign; a log fit could not reach
// it (the same bounds are refused without the flag).
TEST(LogParameterFit, FitsASignedParameterMarkedLinear) {
  const double A = 2.0, tau = 0.5, c = -3.0;
  std::vector<double> t, y;
  for (int i = 0; i <= 40; ++i) {
    t.push_back(0.05 * i);
    y.push_back(A * std::exp(-t.back() / tau) + c);
  }
  shudder::analysis::LogParameterProblem problem;
  problem.residuals = static_cast<int>(t.size());
  problem.lower = {0.1, 0.01, -10.0};
  problem.upper = {10.0, 10.0, 10.0};
  problem.linear = {false, false, true};
  problem.starts = {{1.0, 1.0, 1.0}};
  problem.max_evaluations = 200;
  problem.evaluate = [&](const std::vector<double>& v, Eigen::VectorXd& r) {
    for (std::size_t i = 0; i < t.size(); ++i)
      r[static_cast<Eigen::Index>(i)] = v[0] * std::exp(-t[i] / v[1]) + v[2] - y[i];
    return true;
  };
  const auto fit = shudder::analysis::fit_log_parameters(problem);
  ASSERT_TRUE(fit.feasible);
  EXPECT_NEAR(fit.values[2], c, 1e-4);  // exact data: only LM's stopping rule (0.1 % steps) remains
  EXPECT_NEAR(fit.values[0] / A, 1.0, 1e-3);
  problem.linear.clear();
  EXPECT_THROW(shudder::analysis::fit_log_parameters(problem), std::invalid_argument);
}

TEST(LogParameterFit, AModelThatCannotBeEvaluatedIsInfeasible) {
  shudder::analysis::LogParameterProblem problem;
  problem.residuals = 3;
  problem.lower = {0.1};
  problem.upper = {10.0};
  problem.starts = {{1.0}};
  problem.evaluate = [](const std::vector<double>&, Eigen::VectorXd&) { return false; };
  EXPECT_FALSE(shudder::analysis::fit_log_parameters(problem).feasible);
}

shudder::analysis::DiagnosisResult diagnose_linear(const std::vector<EffectSetting>& truth) {
  const std::vector<DiagnosisRun> runs{shudder::test::linear_measured_run(truth)};
  const auto simulate = [&](const std::vector<EffectSetting>& added, std::size_t k) {
    return shudder::test::linear_prediction(runs[k], added);
  };
  return shudder::analysis::diagnose(runs, shudder::test::linear_candidates(), simulate, DiagnosisOptions{});
}

TEST(DiagnoseLinear, NamesTheMissingEffectAndFitsItsParameter) {
  const double slope = 0.3;  // N m per rpm
  const auto r = diagnose_linear({{"torque_slope", {slope}}});
  ASSERT_EQ(r.missing_effects, std::vector<std::string>{"torque_slope"});
  ASSERT_EQ(r.final_effects.size(), 1u);
  // Linear least squares on 1001 samples with σ = 0.05 N m and speeds up to 100 rpm: the
  // standard error of the slope is σ / √Σv² ≈ 0.05 / 1.8e3 ≈ 3e-5 N m/rpm (1e-4 relative); the
  // tolerance, 1e-3 relative, is 10 of them and leaves room for LM's stopping rule.
  EXPECT_NEAR(r.final_effects[0].parameters.at(0).second / slope, 1.0, 1e-3);
  // The noise was estimated from the data (4 % as in NoiseEstimate), and the final model
  // explains the run to it.
  EXPECT_NEAR(r.noise_torque_Nm / shudder::test::kLinearNoiseTorqueNm, 1.0, 0.1);
  EXPECT_EQ(r.stop.kind, shudder::analysis::StopReason::Kind::kWithinNoise);
  EXPECT_LT(r.final.torque_rms_Nm, 1.1 * r.noise_torque_Nm);
  EXPECT_GT(r.baseline.torque_rms_Nm, 100 * r.noise_torque_Nm);
}

TEST(DiagnoseLinear, TwoEffectsTheDataCannotTellApartAreNeitherNamed) {
  // `torque_twin` changes the model exactly as `torque_slope` does: any data give both the same
  // held-out misfit. Naming the first in order would be a guess: the search stops on the tie,
  // names neither, and says which two (without the rule the first in order would be named).
  const std::vector<DiagnosisRun> runs{shudder::test::linear_measured_run({{"torque_slope", {0.3}}})};
  const auto simulate = [&](const std::vector<EffectSetting>& added, std::size_t k) {
    std::vector<EffectSetting> as_slope = added;
    for (auto& e : as_slope)
      if (e.effect == "torque_twin") e.effect = "torque_slope";
    return shudder::test::linear_prediction(runs[k], as_slope);
  };
  auto candidates = shudder::test::linear_candidates();
  candidates.push_back(candidates[0]);
  candidates.back().name = "torque_twin";
  const auto r = shudder::analysis::diagnose(runs, candidates, simulate, DiagnosisOptions{});
  EXPECT_TRUE(r.missing_effects.empty());
  EXPECT_EQ(r.stop.kind, shudder::analysis::StopReason::Kind::kTie);
  EXPECT_EQ(std::min(r.stop.best_effect, r.stop.tied_with), "torque_slope");
  EXPECT_EQ(std::max(r.stop.best_effect, r.stop.tied_with), "torque_twin");
  EXPECT_EQ(r.verdict, shudder::analysis::DiagnosisVerdict::kNotExplained);
}

TEST(DiagnoseLinear, NamesNothingWhenTheDataEqualTheBaseline) {
  const auto r = diagnose_linear({});
  EXPECT_TRUE(r.missing_effects.empty());
  EXPECT_TRUE(r.final_effects.empty());
  EXPECT_EQ(r.stop.kind, shudder::analysis::StopReason::Kind::kWithinNoise);
  EXPECT_EQ(r.simulations, 1);  // the baseline only: nothing to fit
}

// Two runs whose thermocouple and IR spot see the same smooth warming, each with its own white
// noise; the model reads 2 °C hotter on both thermometers (a model-form gap of the heat balance),
// or additionally 1 °C on the thermocouple alone (a sensor fault).
struct ThermometerPair {
  std::vector<DiagnosisRun> runs;
  shudder::analysis::Predictions common_gap, sensor_fault, exact;
};

ThermometerPair thermometer_pair() {
  ThermometerPair t;
  for (unsigned k = 0; k < 2; ++k) {
    DiagnosisRun r;
    r.name = "run" + std::to_string(k);
    const std::size_t n = 5000;
    const auto tc_noise = white_noise(n, 0.335, 10 + k), ir_noise = white_noise(n, 0.75, 20 + k);
    shudder::analysis::Prediction gap, fault;
    for (std::size_t i = 0; i < n; ++i) {
      const double time = 0.01 * static_cast<double>(i), warm = 80.0 + 20.0 * std::sin(0.05 * time);
      r.time_s.push_back(time);
      r.speed_rpm.push_back(50.0);
      r.normal_force_N.push_back(15000.0);
      r.torque_Nm.push_back(70.0);
      r.temp_C.push_back(warm + tc_noise[i]);
      r.ir_temp_C.push_back(warm + ir_noise[i]);
      gap.torque_Nm.push_back(70.0);
      gap.temp_C.push_back(warm + 2.0);
      gap.ir_temp_C.push_back(warm + 2.0);
    }
    fault = gap;
    for (double& v : fault.temp_C) v += 1.0;
    shudder::analysis::Prediction exact = gap;
    for (double& v : exact.temp_C) v -= 2.0;
    for (double& v : exact.ir_temp_C) v -= 2.0;
    t.exact.push_back(std::move(exact));
    t.runs.push_back(std::move(r));
    t.common_gap.push_back(std::move(gap));
    t.sensor_fault.push_back(std::move(fault));
  }
  return t;
}

const shudder::analysis::Channel* find_channel(const shudder::analysis::MisfitModel& m, const std::string& name) {
  for (const auto& c : m.channels())
    if (c.name == name) return &c;
  return nullptr;
}

TEST(MisfitThermocoupleAgainstIr, OnlyATemperatureToleranceAddsTheChannel) {
  const ThermometerPair t = thermometer_pair();
  DiagnosisOptions plain;
  EXPECT_EQ(find_channel(shudder::analysis::MisfitModel(t.runs, plain), "temp_minus_ir_C"), nullptr);
  DiagnosisOptions torque_only;
  torque_only.tolerance = {{"torque_Nm", 0.5}};
  EXPECT_EQ(find_channel(shudder::analysis::MisfitModel(t.runs, torque_only), "temp_minus_ir_C"), nullptr);
  DiagnosisOptions with;
  with.tolerance = {{"temp_C", 2.0}};
  const shudder::analysis::MisfitModel m(t.runs, with);
  const auto* d = find_channel(m, "temp_minus_ir_C");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->tolerance, 0.0);                             // not temp_C's
  EXPECT_EQ(find_channel(m, "ir_temp_C")->tolerance, 2.0);  // the IR spot keeps it
  // Its noise is the difference's: √(0.335² + 0.75²) = 0.821 °C; 4 % as NoiseEstimate's bound.
  EXPECT_NEAR(d->sigma / std::hypot(0.335, 0.75), 1.0, kNoiseRelTol);
}

TEST(MisfitThermocoupleAgainstIr, CancelsACommonGapAndKeepsAThermocoupleFault) {
  const ThermometerPair t = thermometer_pair();
  DiagnosisOptions with;
  with.tolerance = {{"temp_C", 2.0}};
  const shudder::analysis::MisfitModel m(t.runs, with);
  const auto& d = *find_channel(m, "temp_minus_ir_C");
  const auto& tc = *find_channel(m, "temp_C");
  // A 2 °C gap on both thermometers: temp_C is at its widened scale, J_c = (σ² + 4)/(σ² + 4) ≈ 1
  // (its residual is the 2 °C itself), and the difference sees only its noise, J_c ≈ 1; 10 %
  // covers the sampling of 10,000 samples (≈ 1.4 % standard error of a mean square) and the
  // sigma estimate's 4 %.
  EXPECT_NEAR(m.channel_misfit(tc, m.all(), t.common_gap), 1.0, 0.1);
  EXPECT_NEAR(m.channel_misfit(d, m.all(), t.common_gap), 1.0, 0.1);
  // 1 °C more on the thermocouple alone: against its 2 °C tolerance temp_C reads it as
  // (0.335² + 9)/(0.335² + 4) = 2.2, not far from a gap it already allows; the difference rises
  // by 1/0.821² = 1.48 above its noise. 0.25 = the sigma estimate's 4 % bound, doubled in a
  // square, on J ≈ 2.48.
  EXPECT_NEAR(m.channel_misfit(d, m.all(), t.sensor_fault), 1.0 + 1.0 / (0.335 * 0.335 + 0.75 * 0.75), 0.25);
}

TEST(MisfitThermocoupleAgainstIr, ATolerancedChannelEarnsNothingBelowItsScale) {
  // The noise-free truth: temp_C and ir_temp_C come out far inside their 2 °C tolerance
  // (J_c = σ²/(σ² + 4) ≈ 0.03 and 0.12), the difference at its noise (≈ 1), the torque exact (0).
  // J = ½·0 + ½·mean(1, 1, ≈ 1) ≈ 0.5 with the floor at J_c = 1 for toleranced channels; 0.19
  // without it. 0.05: the difference's J_c within its sampling and sigma estimate (10 %) / 6.
  const ThermometerPair t = thermometer_pair();
  DiagnosisOptions with;
  with.tolerance = {{"temp_C", 2.0}};
  const shudder::analysis::MisfitModel m(t.runs, with);
  EXPECT_NEAR(m.misfit(m.all(), t.exact), 0.5, 0.05);
  // The per-channel J is not floored: it says how far inside the tolerance the model is.
  EXPECT_LT(m.channel_misfit(*find_channel(m, "temp_C"), m.all(), t.exact), 0.1);
}

}  // namespace
