#include "analysis/diagnosis.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>
#include <random>
#include <stdexcept>

#include "analysis/candidate_fit.hpp"
#include "analysis/effect_selection.hpp"
#include "analysis/explanation_check.hpp"
#include "analysis/misfit.hpp"
#include "analysis/noise_estimate.hpp"
#include "analysis/residual_tracking.hpp"
#include "core/parallel_for.hpp"

namespace shudder::analysis {

namespace {

void check_inputs(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates) {
  if (runs.empty()) throw std::invalid_argument("no measured runs given");
  for (const auto& r : runs) {
    const std::size_t n = r.time_s.size();
    if (r.speed_rpm.size() != n || r.normal_force_N.size() != n || r.torque_Nm.size() != n || r.temp_C.size() != n)
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

// A run the baseline model made, as a sensor would have recorded it: its predicted torque,
// temperatures and drive speed plus white noise of the sigmas the measured run shows (the
// speed's read off the measured column alike), and the measured clamp force with fresh noise
// of the sigma it shows. Seeded per run: reproducible.
DiagnosisRun pseudo_run(const DiagnosisRun& measured_run, const Prediction& p, const std::vector<double>& sigmas,
                        std::size_t k) {
  DiagnosisRun pseudo = measured_run;
  std::mt19937 rng(static_cast<unsigned>(1000 + k));
  std::normal_distribution<double> unit(0.0, 1.0);
  const auto noisy = [&](const std::vector<double>& x, double sigma) {
    std::vector<double> y(x);
    for (double& v : y) v += sigma * unit(rng);
    return y;
  };
  pseudo.torque_Nm = noisy(p.torque_Nm, sigmas[0]);
  pseudo.temp_C = noisy(p.temp_C, sigmas[1]);
  if (!measured_run.sump_temp_C.empty() && p.sump_temp_C.size() == p.temp_C.size())
    pseudo.sump_temp_C = noisy(p.sump_temp_C, sigmas[1]);
  if (!measured_run.ir_temp_C.empty() && p.ir_temp_C.size() == p.temp_C.size())
    pseudo.ir_temp_C = noisy(p.ir_temp_C, sigmas[1]);
  const std::vector<double>& speed = p.speed_rpm.size() == p.torque_Nm.size() ? p.speed_rpm : measured_run.speed_rpm;
  pseudo.speed_rpm = noisy(speed, estimate_noise_sigma(measured_run.speed_rpm));
  // The force is the replay's input, not the model's output: the measured one, which already
  // carries the load cell's noise once, gets a second draw, so that the replays of the measured
  // and the pseudo run differ by one force noise as the model and the clutch do. It matters
  // most in a coupling, whose pack turns clamp-force noise into torque n_interfaces times as
  // strongly as the rig's single disc (16 x: 37.5 N of load-cell noise reads ~3 N m); on the
  // rig the replay's 0.05 s force windows average most of it away. Its own stream, so that the
  // other channels' draws do not depend on it; clipped at 0 like the load cell's reading.
  if (const double sigma_N = estimate_noise_sigma(measured_run.normal_force_N); sigma_N > 0) {
    std::mt19937_64 force_rng(2000 + k);
    std::normal_distribution<double> force_noise(0.0, sigma_N);
    for (double& f : pseudo.normal_force_N) f = std::max(0.0, f + force_noise(force_rng));
  }
  return pseudo;
}

// The replay's reproduction error (analysis/misfit.hpp set_reproduction): each run's baseline
// prediction, noised like the data, replayed through the same path.
void measure_reproduction(const std::vector<DiagnosisRun>& runs, const Predictions& baseline,
                          const Reproducer& reproduce, MisfitModel& misfit, unsigned jobs) {
  const std::vector<double> sigmas{misfit.channels()[0].sigma, misfit.channels()[1].sigma};
  Predictions replayed(runs.size());
  parallel_for(runs.size(), jobs, [&](std::size_t k) {
    if (!baseline[k]) return;
    try {
      replayed[k] = reproduce(pseudo_run(runs[k], *baseline[k], sigmas, k), k);
    } catch (const std::exception&) {
      replayed[k].reset();  // not reproducible: that run's scale keeps noise and tolerance only
    }
  });
  misfit.set_reproduction(baseline, replayed);
}

// Speed in rad/s under speed_rpm: the friction heat is torque × speed, so the model heats
// 9.55 × too little. Missing effects (oil cooling, rig mass, sensor lag) make the measured rise
// SMALLER than the model's, not larger; a measured rise 6–15 × the baseline's (9.55 ± the
// spread of rise ratios that other missing effects give, about ×1.5) is read as a unit
// error, a larger ratio only warned about. Runs whose rise is under 2 °C or 10 σ are skipped.
void check_speed_units(const std::vector<DiagnosisRun>& runs, const Predictions& baseline, double sigma_temp_C,
                       std::vector<std::string>& warnings) {
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!baseline[k]) continue;
    const auto& m = runs[k].temp_C;
    const auto& p = baseline[k]->temp_C;
    const auto rise = [](const std::vector<double>& x) {
      const std::size_t n = std::max<std::size_t>(1, x.size() / 20);
      double a = 0, top = -1e300;
      for (std::size_t i = 0; i < n; ++i) a += x[i] / static_cast<double>(n);
      for (double v : x) top = std::max(top, v);
      return top - a;
    };
    const double measured_rise = rise(m), model_rise = rise(p);
    if (measured_rise < std::max(2.0, 10.0 * sigma_temp_C) || model_rise <= 0) continue;
    const double ratio = measured_rise / model_rise;
    char buf[200];
    std::snprintf(buf, sizeof buf, "run '%s': its temperature rises %.3g C, %.3g x the %.3g C the model predicts",
                  runs[k].name.c_str(), measured_rise, ratio, model_rise);
    if (ratio >= 6.0 && ratio <= 15.0)
      throw std::invalid_argument(std::string(buf) +
                                  "; a speed_rpm column in rad/s reads 9.55 x low: give the speed in rpm");
    if (ratio > 15.0) warnings.push_back(std::string(buf) + "; check the units of speed_rpm and torque_Nm");
  }
}

DiagnosisVerdict verdict_of(const std::vector<ChannelFit>& channels, bool effects_named) {
  bool within = true;
  for (const auto& c : channels) within = within && c.within;
  if (within) return DiagnosisVerdict::kExplained;
  return effects_named ? DiagnosisVerdict::kPartlyExplained : DiagnosisVerdict::kNotExplained;
}

// The method, free of clocks: baseline, reproduction error, greedy selection, the final
// comparison and the verdict.
DiagnosisResult run_diagnosis(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
                              const Simulator& simulate, const DiagnosisOptions& opt, const Reproducer& reproduce) {
  check_inputs(runs, candidates);
  DiagnosisResult r;
  for (const auto& run : runs) r.runs.push_back(run.name);

  MisfitModel misfit(runs, opt);
  r.noise_torque_Nm = misfit.channels()[0].sigma;
  r.noise_temp_C = misfit.channels()[1].sigma;
  r.holdout = misfit.holdout_split();
  const CandidateFitter fitter(runs, candidates, simulate, misfit, opt);

  const Predictions baseline = fitter.predict({}, misfit.all().runs(), opt.jobs);
  check_speed_units(runs, baseline, r.noise_temp_C, r.warnings);
  if (reproduce) measure_reproduction(runs, baseline, reproduce, misfit, opt.jobs);
  const double torque_scale = misfit.pointwise_scale(misfit.channels()[0]);
  const double temp_scale = misfit.pointwise_scale(misfit.channels()[1]);
  r.baseline = misfit.rms(misfit.all(), baseline);
  r.baseline_holdout_misfit = misfit.misfit(misfit.holdout(), baseline);
  r.disagreements = disagreements(runs, baseline, torque_scale, temp_scale);
  r.tracking = tracking(runs, baseline);

  Selection sel = select_effects(runs, candidates, fitter, misfit, opt, baseline);
  for (const auto& st : sel.steps) {
    r.missing_effects.push_back(st.effect);
    r.missing_effects.insert(r.missing_effects.end(), st.joint_with.begin(), st.joint_with.end());
  }
  r.steps = std::move(sel.steps);
  r.last_round = std::move(sel.last_round);
  r.withdrawn = std::move(sel.withdrawn);
  r.indistinguishable = std::move(sel.indistinguishable);
  r.stop = std::move(sel.stop);
  r.tolerance_given = !opt.tolerance.empty();

  const auto channel_fits = [&](const Predictions& final_pred) {
    std::vector<ChannelFit> out;
    for (const auto& c : misfit.channels()) {
      ChannelFit f;
      f.signal = c.name;
      f.comparison = c.blocks ? "block_statistics" : "pointwise";
      f.noise = c.sigma;
      f.baseline_rms = misfit.channel_rms(c, misfit.all(), baseline);
      f.final_rms = misfit.channel_rms(c, misfit.all(), final_pred);
      f.baseline_misfit = misfit.channel_misfit(c, misfit.all(), baseline);
      f.final_misfit = misfit.channel_misfit(c, misfit.all(), final_pred);
      f.error_scale = misfit.channel_scale(c, misfit.all());
      f.reproduction = misfit.reproduction_rms(c);
      f.tolerance = c.tolerance;
      f.within = f.final_misfit <= opt.noise_tolerance * opt.noise_tolerance;
      out.push_back(f);
    }
    return out;
  };
  r.channels = channel_fits(sel.full_predictions);
  // Named only when found (analysis/explanation_check.hpp): otherwise nothing is named and the
  // final model is the baseline.
  r.not_explained = unexplained_effects(sel.full, fitter, r.channels, opt);
  const bool found = r.not_explained.empty();
  const Predictions& full_pred = found ? sel.full_predictions : baseline;
  if (found) {
    for (const auto& e : sel.full) {
      FittedEffect f{e.effect, {}};
      const auto& c = fitter.candidate(e.effect);
      for (std::size_t j = 0; j < e.values.size(); ++j) f.parameters.emplace_back(c.parameter_names[j], e.values[j]);
      r.final_effects.push_back(std::move(f));
    }
  } else {
    r.missing_effects.clear();
    r.channels = channel_fits(baseline);
  }
  r.final = misfit.rms(misfit.all(), full_pred);
  r.verdict = found ? verdict_of(r.channels, !r.missing_effects.empty()) : DiagnosisVerdict::kNotExplained;
  r.final_holdout_misfit = misfit.misfit(misfit.holdout(), found ? sel.fold_predictions : baseline);
  r.final_disagreements = disagreements(runs, full_pred, torque_scale, temp_scale);

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
DiagnosisResult diagnose(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
                         const Simulator& simulate, const DiagnosisOptions& options, const Reproducer& reproduce) {
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
  const Reproducer timed_reproduce = !reproduce ? Reproducer{} : [&](const DiagnosisRun& pseudo, std::size_t run) {
    const double t0 = thread_cpu_s();
    Prediction p = reproduce(pseudo, run);
    const double dt = thread_cpu_s() - t0;
    const std::lock_guard lock(timing_mutex);
    simulation_thread_s += dt;
    ++simulations;
    return p;
  };
  DiagnosisResult r = run_diagnosis(runs, candidates, timed, options, timed_reproduce);
  r.simulations = simulations;
  r.simulation_thread_s = simulation_thread_s;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  r.fitting_thread_s = std::max(0.0, cpu_s - r.simulation_thread_s);
  return r;
}

}  // namespace shudder::analysis
