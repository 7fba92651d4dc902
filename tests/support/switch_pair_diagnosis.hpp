#pragma once
// A diagnosis problem with two parameter-free switches that are right only together (the
// joint step's case, analysis/joint_step.hpp), for fast tests of the search and its costs:
//
//   three runs at "load" L = 10, 25 (fit) and 15 (held out), speed 50 rpm, 100 Hz
//   baseline   torque = 100 N m, temp = 20 °C + 1 K/s · t
//   warm       torque += 1 + 0.2 t        (a switch: friction following the temperature rise)
//   load       torque −= 0.15 L           (a switch: friction falling with the load)
//   gain       torque × g                 (one parameter: a torque-cell gain)
//
// The "measured" runs are the model with chosen effects plus seeded white noise
// (σ_torque = 0.1 N m, σ_temp = 0.05 K).

#include <random>
#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"

namespace shudder::test {

/// The switch-pair model's prediction of `run` with `added` effects on top of the baseline.
inline analysis::Prediction switch_pair_prediction(const analysis::DiagnosisRun& run,
                                                   const std::vector<analysis::EffectSetting>& added) {
  analysis::Prediction p;
  const double load = run.normal_force_N.front() / 1000.0;
  for (double t : run.time_s) {
    double torque = 100.0;
    for (const auto& e : added) {
      if (e.effect == "warm") torque += 1.0 + 0.2 * t;
      if (e.effect == "load") torque -= 0.15 * load;
    }
    for (const auto& e : added)
      if (e.effect == "gain") torque *= e.values[0];
    p.torque_Nm.push_back(torque);
    p.temp_C.push_back(20.0 + 1.0 * t);
  }
  return p;
}

/// gain, warm and load, in that order.
inline std::vector<analysis::EffectCandidate> switch_pair_candidates() {
  return {{"gain", "the torque cell reads a fraction high or low", {"g"}, {{0.97}, {1.03}}, {0.5}, {2.0}, {}},
          {"warm", "friction follows the temperature rise", {}, {}, {}, {}, {}},
          {"load", "friction falls with the load", {}, {}, {}, {}, {}}};
}

/// The three "measured" runs (L10, L25, then the held-out L15; names plus `name_suffix`) of
/// `samples` + 1 samples with `hidden` on, noise drawn from one stream seeded `seed`.
inline std::vector<analysis::DiagnosisRun> switch_pair_runs(const std::vector<analysis::EffectSetting>& hidden,
                                                            int samples, unsigned seed,
                                                            const std::string& name_suffix = "") {
  std::vector<analysis::DiagnosisRun> runs;
  std::mt19937 rng(seed);
  std::normal_distribution<double> torque_noise(0.0, 0.1), temp_noise(0.0, 0.05);
  const struct {
    double load;
    const char* name;
  } spec[] = {{10.0, "L10"}, {25.0, "L25"}, {15.0, "L15"}};
  for (const auto& [load, name] : spec) {
    analysis::DiagnosisRun run;
    run.name = name + name_suffix;
    for (int i = 0; i <= samples; ++i) {
      run.time_s.push_back(0.01 * i);
      run.speed_rpm.push_back(50.0);
      run.normal_force_N.push_back(1000.0 * load);
    }
    const analysis::Prediction truth = switch_pair_prediction(run, hidden);
    for (std::size_t i = 0; i < run.time_s.size(); ++i) {
      run.torque_Nm.push_back(truth.torque_Nm[i] + torque_noise(rng));
      run.temp_C.push_back(truth.temp_C[i] + temp_noise(rng));
    }
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace shudder::test
