#include "analysis/diagnosis.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <mutex>
#include <stdexcept>

#include "analysis/candidate_fit.hpp"
#include "analysis/effect_selection.hpp"
#include "analysis/misfit.hpp"
#include "analysis/residual_tracking.hpp"

namespace shudder::analysis {

namespace {

void check_inputs(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates) {
  if (runs.empty()) throw std::invalid_argument("no measured runs given");
  for (const auto& r : runs) {
    const std::size_t n = r.time_s.size();
    if (r.speed_rpm.size() != n || r.normal_force_N.size() != n || r.torque_Nm.size() != n ||
        r.temp_C.size() != n)
      throw std::invalid_argument("run '" + r.name + "': columns differ in length");
    if (n < 20)
      throw std::invalid_argument("run '" + r.name + "' has " + std::to_string(n) +
                                  " samples; at least 20 are needed to fit and hold out anything");
  }
  for (std::size_t i = 0; i < candidates.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (candidates[i].name == candidates[j].name)
        throw std::invalid_argument("candidate effect '" + candidates[i].name + "' given twice");
}

// The method, free of clocks: baseline, greedy selection, the final comparison.
DiagnosisResult run_diagnosis(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
                              const Simulator& simulate, const DiagnosisOptions& opt) {
  check_inputs(runs, candidates);
  DiagnosisResult r;
  for (const auto& run : runs) r.runs.push_back(run.name);

  const MisfitModel misfit(runs, opt);
  r.noise_torque_Nm = misfit.channels()[0].sigma;
  r.noise_temp_C = misfit.channels()[1].sigma;
  r.holdout = misfit.holdout_split();
  const CandidateFitter fitter(runs, candidates, simulate, misfit, opt);

  const Predictions baseline = fitter.predict({}, misfit.all().runs(), opt.jobs);
  r.baseline = misfit.rms(misfit.all(), baseline);
  r.baseline_holdout_misfit = misfit.misfit(misfit.holdout(), baseline);
  r.disagreements = disagreements(runs, baseline, r.noise_torque_Nm, r.noise_temp_C);
  r.tracking = tracking(runs, baseline);

  Selection sel = select_effects(runs, candidates, fitter, misfit, opt, baseline);
  const Predictions& full_pred = sel.full_predictions;
  for (const auto& st : sel.steps) r.missing_effects.push_back(st.effect);
  r.steps = std::move(sel.steps);
  r.last_round = std::move(sel.last_round);
  r.stop = std::move(sel.stop);

  r.final = misfit.rms(misfit.all(), full_pred);
  for (const auto& e : sel.full) {
    FittedEffect f{e.effect, {}};
    const auto& c = fitter.candidate(e.effect);
    for (std::size_t j = 0; j < e.values.size(); ++j) f.parameters.emplace_back(c.parameter_names[j], e.values[j]);
    r.final_effects.push_back(std::move(f));
  }
  for (const auto& c : misfit.channels()) {
    ChannelFit f;
    f.signal = c.name;
    f.comparison = c.blocks ? "block_statistics" : "pointwise";
    f.noise = c.sigma;
    f.baseline_rms = misfit.channel_rms(c, misfit.all(), baseline);
    f.final_rms = misfit.channel_rms(c, misfit.all(), full_pred);
    f.baseline_misfit = misfit.channel_misfit(c, misfit.all(), baseline);
    f.final_misfit = misfit.channel_misfit(c, misfit.all(), full_pred);
    r.channels.push_back(f);
  }
  r.final_holdout_misfit = misfit.misfit(misfit.holdout(), sel.fold_predictions);
  r.final_disagreements = disagreements(runs, full_pred, r.noise_torque_Nm, r.noise_temp_C);

  for (std::size_t k = 0; k < runs.size(); ++k) {
    RunTraces t;
    t.run = runs[k].name;
    for (std::size_t i : misfit.all().index[k]) {
      t.time_s.push_back(runs[k].time_s[i]);
      t.torque_measured.push_back(runs[k].torque_Nm[i]);
      t.torque_baseline.push_back(baseline[k]->torque_Nm[i]);
      t.torque_final.push_back(full_pred[k]->torque_Nm[i]);
      t.temp_measured.push_back(runs[k].temp_C[i]);
      t.temp_baseline.push_back(baseline[k]->temp_C[i]);
      t.temp_final.push_back(full_pred[k]->temp_C[i]);
    }
    r.traces.push_back(std::move(t));
  }
  return r;
}

// CPU time of the calling thread: simulations are timed by what they cost, not by how long
// they waited for a core.
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

// Every clock of the diagnosis is read here: the wall time and process CPU time around the
// method, and each simulation's thread CPU time through a wrapper of the Simulator.
DiagnosisResult diagnose(const std::vector<DiagnosisRun>& runs,
                         const std::vector<EffectCandidate>& candidates, const Simulator& simulate,
                         const DiagnosisOptions& options) {
  const std::clock_t cpu0 = std::clock();
  const auto wall0 = std::chrono::steady_clock::now();
  std::mutex timing_mutex;
  double simulation_thread_s = 0.0;
  long simulations = 0;
  const Simulator timed = [&](const std::vector<EffectSetting>& added, std::size_t run) {
    const double t0 = thread_cpu_s();
    Prediction p = simulate(added, run);
    const double dt = thread_cpu_s() - t0;
    const std::lock_guard lock(timing_mutex);
    simulation_thread_s += dt;
    ++simulations;
    return p;
  };
  DiagnosisResult r = run_diagnosis(runs, candidates, timed, options);
  r.simulations = simulations;
  r.simulation_thread_s = simulation_thread_s;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  r.fitting_thread_s = std::max(0.0, cpu_s - r.simulation_thread_s);
  return r;
}

}  // namespace shudder::analysis
