#pragma once
// A diagnosis problem whose answer is known, for fast tests of analysis::diagnose and its
// writers: a fake "model" that is linear in its effects' parameters.
//
//   baseline      torque = 50 N m,                     temp = 20 °C + 0.1 K/s · t
//   torque_slope  torque += a · speed_rpm              (a in N m/rpm)
//   extra_heating temp   += b · t                      (b in K/s)
//
// One run of 10 s at 100 Hz, speed ramping 1 → 100 rpm at 10 kN. The "measured" run is the
// model with chosen effects plus seeded white noise (σ_torque = 0.05 N m, σ_temp = 0.02 K).

#include <cmath>
#include <random>
#include <vector>

#include "analysis/diagnosis.hpp"

namespace shudder::test {

inline constexpr double kLinearNoiseTorqueNm = 0.05, kLinearNoiseTempC = 0.02;

inline std::vector<analysis::EffectCandidate> linear_candidates() {
  return {{"torque_slope",
           "torque rises with the sliding speed",
           {"slope_Nm_per_rpm"},
           {{0.05}, {1.0}},
           {1e-3},
           {10.0},
           {}},
          {"extra_heating", "the discs heat faster", {"rate_K_per_s"}, {{0.05}, {1.0}}, {1e-3}, {10.0}, {}}};
}

/// The linear model's prediction of `run` with `added` effects on top of the baseline.
inline analysis::Prediction linear_prediction(const analysis::DiagnosisRun& run,
                                              const std::vector<analysis::EffectSetting>& added) {
  analysis::Prediction p;
  for (std::size_t i = 0; i < run.time_s.size(); ++i) {
    p.torque_Nm.push_back(50.0);
    p.temp_C.push_back(20.0 + 0.1 * run.time_s[i]);
  }
  for (const auto& e : added)
    for (std::size_t i = 0; i < run.time_s.size(); ++i) {
      if (e.effect == "torque_slope") p.torque_Nm[i] += e.values[0] * run.speed_rpm[i];
      if (e.effect == "extra_heating") p.temp_C[i] += e.values[0] * run.time_s[i];
    }
  return p;
}

/// The measured run: the model with `truth` plus seeded noise.
inline analysis::DiagnosisRun linear_measured_run(const std::vector<analysis::EffectSetting>& truth,
                                                  unsigned seed = 7) {
  analysis::DiagnosisRun run;
  run.name = "linear.csv";
  for (int i = 0; i <= 1000; ++i) {
    const double t = 0.01 * i;
    run.time_s.push_back(t);
    run.speed_rpm.push_back(1.0 + 9.9 * t);
    run.normal_force_N.push_back(10000.0);
  }
  const analysis::Prediction p = linear_prediction(run, truth);
  std::mt19937 rng(seed);
  std::normal_distribution<double> torque_noise(0.0, kLinearNoiseTorqueNm), temp_noise(0.0, kLinearNoiseTempC);
  for (std::size_t i = 0; i < run.time_s.size(); ++i) {
    run.torque_Nm.push_back(p.torque_Nm[i] + torque_noise(rng));
    run.temp_C.push_back(p.temp_C[i] + temp_noise(rng));
  }
  return run;
}

}  // namespace shudder::test
