// The pseudo runs of the reproduction check (analysis/diagnosis.cpp pseudo_run): the clamp force
// they hand the reproducer is the measured one with fresh noise of the sigma it shows, the same
// way for every run (it was added only in a coupling's replay before), clipped at 0; a
// noise-free force is left as it is. Checked with a fake reproducer that records what it gets.
//
//   runs        10 s at 100 Hz (1001 samples), constant speed, torque and temperature
//   force       A: 10 kN + white noise of 40 N;  B: 20 N + 40 N (readings clipped at 0 happen);
//               C: 10 kN, noise free
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <random>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "analysis/noise_estimate.hpp"

namespace shudder::analysis {
namespace {

Prediction flat_prediction(std::size_t n) {
  Prediction p;
  p.torque_Nm.assign(n, 50.0);
  p.temp_C.assign(n, 40.0);
  return p;
}

struct Recorded {
  std::vector<DiagnosisRun> runs;
  std::vector<std::vector<double>> pseudo_force_N;
};

Recorded reproduce_runs() {
  Recorded out;
  std::mt19937 rng(5);
  std::normal_distribution<double> unit(0.0, 1.0);
  const struct {
    const char* name;
    double force_N, sigma_N;
  } spec[] = {{"A", 10000.0, 40.0}, {"B", 20.0, 40.0}, {"C", 10000.0, 0.0}};
  for (const auto& s : spec) {
    DiagnosisRun run;
    run.name = s.name;
    for (int i = 0; i <= 1000; ++i) {
      run.time_s.push_back(0.01 * i);
      run.speed_rpm.push_back(50.0);
      run.normal_force_N.push_back(s.force_N + s.sigma_N * unit(rng));
      run.torque_Nm.push_back(50.0 + 0.1 * unit(rng));
      run.temp_C.push_back(40.0 + 0.05 * unit(rng));
    }
    out.runs.push_back(std::move(run));
  }
  out.pseudo_force_N.resize(out.runs.size());
  std::mutex m;
  const auto simulate = [&](const std::vector<EffectSetting>&, std::size_t k) {
    return flat_prediction(out.runs[k].time_s.size());
  };
  const Reproducer reproduce = [&](const DiagnosisRun& pseudo, std::size_t k) {
    const std::lock_guard lock(m);
    out.pseudo_force_N[k] = pseudo.normal_force_N;
    return flat_prediction(pseudo.time_s.size());
  };
  diagnose(out.runs, {}, simulate, DiagnosisOptions{}, reproduce);
  return out;
}

TEST(PseudoRunNoise, TheForceGetsFreshNoiseOfTheSigmaItShows) {
  const Recorded r = reproduce_runs();
  const auto& measured = r.runs[0].normal_force_N;
  const auto& pseudo = r.pseudo_force_N[0];
  ASSERT_EQ(pseudo.size(), measured.size());
  double sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < pseudo.size(); ++i) {
    const double d = pseudo[i] - measured[i];
    sum += d;
    sum2 += d * d;
  }
  const double n = static_cast<double>(pseudo.size());
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  const double sigma = estimate_noise_sigma(measured);  // what the draws are scaled to
  EXPECT_NEAR(sigma, 40.0, 4.0);                        // the MAD estimate of 1001 samples scatters ~4 % (1 sigma)
  // 1001 draws: the sample sd scatters 2.2 % and the mean sigma / 31.6 (1 sigma); 5 of each.
  EXPECT_NEAR(sd / sigma, 1.0, 0.11);
  EXPECT_NEAR(mean, 0.0, 5.0 * sigma / std::sqrt(n));
}

TEST(PseudoRunNoise, EveryRunGetsItsOwnDrawsAndReadingsStayNonNegative) {
  const Recorded r = reproduce_runs();
  // Run B's noise is not run A's (seeded per run): the first differences disagree.
  EXPECT_NE(r.pseudo_force_N[0][0] - r.runs[0].normal_force_N[0], r.pseudo_force_N[1][0] - r.runs[1].normal_force_N[0]);
  const auto& b = r.pseudo_force_N[1];
  EXPECT_GE(*std::min_element(b.begin(), b.end()), 0.0);
  EXPECT_GT(std::count(b.begin(), b.end(), 0.0), 0);  // 20 N ± 57 N: clipped readings occur
  // Reproducible: the same draws on a second diagnosis.
  EXPECT_EQ(reproduce_runs().pseudo_force_N, r.pseudo_force_N);
}

TEST(PseudoRunNoise, ANoiseFreeForceIsLeftAsMeasured) {
  const Recorded r = reproduce_runs();
  EXPECT_EQ(r.pseudo_force_N[2], r.runs[2].normal_force_N);
}

}  // namespace
}  // namespace shudder::analysis
