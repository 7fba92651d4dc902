#include "analysis/diagnosis.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "analysis/log_parameter_fit.hpp"
#include "analysis/residual_analysis.hpp"

namespace shudder::analysis {

namespace {

using Clock = std::chrono::steady_clock;
using Config = std::vector<EffectSetting>;
using Predictions = std::vector<std::optional<Prediction>>;  // per run; empty = not simulated

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU time of the calling thread: simulations are timed by what they cost, not by how long
// they waited for a core.
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string fmt(double v, const char* f = "%.3g") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

/// Sample indices and statistics blocks per run (empty for a run outside the set).
struct SampleSet {
  std::vector<std::vector<std::size_t>> index;
  std::vector<std::vector<std::size_t>> blocks;  // indices into Engine::stat_blocks_[run]
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& i : index) n += i.size();
    return n;
  }
  std::vector<std::size_t> runs() const {
    std::vector<std::size_t> r;
    for (std::size_t k = 0; k < index.size(); ++k)
      if (!index[k].empty()) r.push_back(k);
    return r;
  }
};

/// Runs the work items on `jobs` threads (items are independent).
template <class Fn>
void parallel_for(std::size_t n, unsigned jobs, Fn&& fn) {
  const unsigned threads = std::max(1u, std::min<unsigned>(jobs, static_cast<unsigned>(n)));
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (std::size_t i; (i = next++) < n;) {
        try {
          fn(i);
        } catch (...) {
          std::lock_guard lock(error_mutex);
          if (!error) error = std::current_exception();
        }
      }
    });
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

class Engine {
 public:
  Engine(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
         const Simulator& sim, const DiagnosisOptions& opt)
      : runs_(runs), candidates_(candidates), sim_(sim), opt_(opt) {}

  DiagnosisResult run();

 private:
  struct Outcome {
    CandidateScore score;
    Config config;               // the effects added so far, refitted with it, plus it (last)
    Predictions predictions;     // fit and hold-out runs at the fitted values
    bool ok = false;
  };

  enum class Field { kTorque, kTemp, kSump, kIr };
  struct Channel {
    Field field;
    std::string name;
    double sigma = 0.0;
    bool blocks = false;  // compared by block statistics
  };
  struct BlockStats {
    double mean = 0.0, std = 0.0;
  };
  static const std::vector<double>& measured(const DiagnosisRun& r, Field f);
  static const std::vector<double>& predicted(const Prediction& p, Field f);
  struct StatBlock;
  static double hann(double t_s, const StatBlock& b);
  BlockStats stats(const std::vector<double>& x, std::size_t run, std::size_t block) const;
  std::pair<double, double> channel_sums(const Channel& c, const SampleSet& set, const Predictions& p,
                                         std::vector<double>* entries) const;
  void check_inputs() const;
  void choose_channels();
  void build_sample_sets(DiagnosisResult& r);
  void estimate_block_jitter(const Channel& c);
  Predictions simulate(const Config& config, const std::vector<std::size_t>& which, unsigned jobs) const;
  double misfit(const SampleSet& set, const Predictions& p) const;
  double channel_weight(const Channel& c) const;
  Misfit rms(const SampleSet& set, const Predictions& p) const;
  bool residual_vector(const SampleSet& set, const Predictions& p, Eigen::VectorXd& out) const;
  std::size_t residual_count(const SampleSet& set) const;
  double channel_misfit(const Channel& c, const SampleSet& set, const Predictions& p) const;
  // The fitted parameters of a configuration as one vector, with their bounds, for the solver.
  struct FlatConfig {
    Config config;
    std::vector<std::pair<std::size_t, std::size_t>> slots;  // (effect, parameter) of config
    std::vector<double> values, lower, upper;
    Config with(const std::vector<double>& v) const;
  };
  FlatConfig flatten(const Config& config) const;
  /// Least squares on `set` from the starts; nullopt when no start could be simulated.
  std::optional<Config> fit_config(const FlatConfig& flat, std::vector<std::vector<double>> starts,
                                   const SampleSet& set, unsigned jobs, int& evaluations) const;
  Outcome fit_candidate(const EffectCandidate& c, const Config& fold, const Predictions& current) const;
  Config refit_all(const Config& full, const Config& fold_added, Predictions& out) const;
  double signature_correlation(const Predictions& current, const Predictions& candidate) const;
  std::vector<std::pair<std::string, double>> pooled_tracking(const Predictions& p, bool torque) const;
  std::vector<Disagreement> disagreements(const Predictions& p) const;
  std::vector<Tracking> tracking(const Predictions& p) const;
  std::string reason(const DiagnosisStep& step, const Predictions& current) const;
  const EffectCandidate& candidate(const std::string& name) const;

  const std::vector<DiagnosisRun>& runs_;
  const std::vector<EffectCandidate>& candidates_;
  const Simulator& sim_;
  const DiagnosisOptions& opt_;
  double sigma_torque_ = 0, sigma_temp_ = 0;
  std::vector<Channel> channels_;
  // A statistics block: samples [first, end) weighted by a Hann window over [t0_s, t0_s + length_s].
  struct StatBlock {
    std::size_t first, end;
    double t0_s, length_s;
    double n_eff;  // (Σw)² / Σw²: the sample count whose plain mean has the same noise
  };
  std::vector<std::vector<StatBlock>> stat_blocks_;  // per run
  // Per run: variance of the block mean and block spread beyond what sensor noise explains.
  std::vector<BlockStats> block_jitter_var_;
  SampleSet all_, fit_, holdout_;
  mutable std::mutex timing_mutex_;
  mutable double sim_thread_s_ = 0;
  mutable long simulations_ = 0;
};

void Engine::check_inputs() const {
  if (runs_.empty()) throw std::invalid_argument("no measured runs given");
  for (const auto& r : runs_) {
    const std::size_t n = r.time_s.size();
    if (r.speed_rpm.size() != n || r.normal_force_N.size() != n || r.torque_Nm.size() != n ||
        r.temp_C.size() != n)
      throw std::invalid_argument("run '" + r.name + "': columns differ in length");
    if (n < 20)
      throw std::invalid_argument("run '" + r.name + "' has " + std::to_string(n) +
                                  " samples; at least 20 are needed to fit and hold out anything");
  }
  for (std::size_t i = 0; i < candidates_.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (candidates_[i].name == candidates_[j].name)
        throw std::invalid_argument("candidate effect '" + candidates_[i].name + "' given twice");
}

// The block statistics of a steady signal scatter by the sensor noise alone (σ²/n); a cycle
// that is not a whole number of times in a block adds a jitter that model and measurement
// each have (hence the factor 2 where it is used). Its size is read off the measured
// statistics with the same second-difference estimator as the sensor noise (trends and
// single kinks drop out), less the noise part. Fewer than 5 blocks: no estimate, noise only.
void Engine::estimate_block_jitter(const Channel& c) {
  block_jitter_var_.assign(runs_.size(), {});
  if (!c.blocks) return;
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    const std::size_t nb = stat_blocks_[k].size();
    if (nb < 5) continue;
    std::vector<double> means, spreads;
    double noise_var = 0;
    for (std::size_t b = 0; b < nb; ++b) {
      const BlockStats s = stats(measured(runs_[k], c.field), k, b);
      means.push_back(s.mean);
      spreads.push_back(s.std);
      noise_var += c.sigma * c.sigma / stat_blocks_[k][b].n_eff / static_cast<double>(nb);
    }
    block_jitter_var_[k] = {std::max(0.0, std::pow(estimate_noise_sigma(means), 2) - noise_var),
                            std::max(0.0, std::pow(estimate_noise_sigma(spreads), 2) - 0.5 * noise_var)};
  }
}

void Engine::build_sample_sets(DiagnosisResult& r) {
  const std::size_t nr = runs_.size();
  for (SampleSet* set : {&all_, &fit_, &holdout_}) {
    set->index.assign(nr, {});
    set->blocks.assign(nr, {});
  }
  stat_blocks_.assign(nr, {});
  for (std::size_t k = 0; k < nr; ++k) {
    const auto& t = runs_[k].time_s;
    const std::size_t n = t.size();
    const std::size_t stride =
        std::max<std::size_t>(1, (n + opt_.max_samples_per_run - 1) / std::max(1, opt_.max_samples_per_run));
    for (std::size_t i = 0; i < n; i += stride) all_.index[k].push_back(i);
    // Statistics blocks: Hann windows of statistics_block_s every half length, the last one
    // ending at the run's end; a run shorter than one block is one block.
    const double length = std::min(opt_.statistics_block_s, t.back() - t.front());
    std::vector<double> starts;
    for (double t0 = t.front(); t0 + length <= t.back() + 1e-9 * length; t0 += 0.5 * length)
      starts.push_back(t0);
    if (starts.empty() || starts.back() + length < t.back() - 0.25 * length)
      starts.push_back(t.back() - length);
    for (double t0 : starts) {
      StatBlock blk{0, 0, t0, length, 0.0};
      blk.first = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), t0) - t.begin());
      blk.end = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), t0 + length) - t.begin());
      double sw = 0, sw2 = 0;
      for (std::size_t i = blk.first; i < blk.end; ++i) {
        const double w = hann(t[i], blk);
        sw += w;
        sw2 += w * w;
      }
      blk.n_eff = sw2 > 0 ? sw * sw / sw2 : 0.0;
      if (blk.end - blk.first >= 10 && blk.n_eff > 0) {
        all_.blocks[k].push_back(stat_blocks_[k].size());
        stat_blocks_[k].push_back(blk);
      }
    }
  }
  if (nr > 1) {
    for (std::size_t k = 0; k + 1 < nr; ++k) {
      fit_.index[k] = all_.index[k];
      fit_.blocks[k] = all_.blocks[k];
    }
    holdout_.index[nr - 1] = all_.index[nr - 1];
    holdout_.blocks[nr - 1] = all_.blocks[nr - 1];
    r.holdout = "run '" + runs_.back().name + "' (fits use the other runs)";
    return;
  }
  // One run: alternate tenths of its duration; hold out the odd ones.
  const auto& t = runs_[0].time_s;
  const double tenth = (t.back() - t.front()) / 10.0;
  const auto odd = [&](double time) {
    return std::min(9, static_cast<int>((time - t.front()) / tenth)) % 2 == 1;
  };
  for (std::size_t i : all_.index[0]) (odd(t[i]) ? holdout_ : fit_).index[0].push_back(i);
  for (std::size_t b : all_.blocks[0]) {
    const StatBlock& blk = stat_blocks_[0][b];
    (odd(blk.t0_s + 0.5 * blk.length_s) ? holdout_ : fit_).blocks[0].push_back(b);
  }
  const bool blocks_needed = opt_.torque_block_statistics;
  if (fit_.size() < 10 || holdout_.size() < 10 ||
      (blocks_needed && (fit_.blocks[0].empty() || holdout_.blocks[0].empty())))
    throw std::invalid_argument("run '" + runs_[0].name +
                                "' is too short to split into fitted and held-out time (needs 20 samples)");
  r.holdout = "odd tenths of the run's time (fits use the even tenths)";
}

Predictions Engine::simulate(const Config& config, const std::vector<std::size_t>& which,
                             unsigned jobs) const {
  Predictions out(runs_.size());
  parallel_for(which.size(), jobs, [&](std::size_t i) {
    const std::size_t k = which[i];
    const double t0 = thread_cpu_s();
    Prediction p = sim_(config, k);
    const double dt = thread_cpu_s() - t0;
    {
      std::lock_guard lock(timing_mutex_);
      sim_thread_s_ += dt;
      ++simulations_;
    }
    const std::size_t n = runs_[k].time_s.size();
    bool ok = true;
    for (const auto& c : channels_) ok = ok && predicted(p, c.field).size() == n;
    if (!ok)
      throw std::runtime_error("the simulator returned a prediction of the wrong length for run '" +
                               runs_[k].name + "'");
    out[k] = std::move(p);
  });
  return out;
}

const std::vector<double>& Engine::measured(const DiagnosisRun& r, Field f) {
  switch (f) {
    case Field::kTorque: return r.torque_Nm;
    case Field::kTemp: return r.temp_C;
    case Field::kSump: return r.sump_temp_C;
    case Field::kIr: return r.ir_temp_C;
  }
  return r.torque_Nm;
}

const std::vector<double>& Engine::predicted(const Prediction& p, Field f) {
  switch (f) {
    case Field::kTorque: return p.torque_Nm;
    case Field::kTemp: return p.temp_C;
    case Field::kSump: return p.sump_temp_C;
    case Field::kIr: return p.ir_temp_C;
  }
  return p.torque_Nm;
}

// A Hann window keeps a cycle that does not fit a whole number of times into the block out of
// its mean and spread (leakage falls as 1/(cycles per block)³ instead of 1/cycles).
double Engine::hann(double t_s, const StatBlock& b) {
  const double s = std::sin(std::numbers::pi * (t_s - b.t0_s) / b.length_s);
  return s * s;
}

Engine::BlockStats Engine::stats(const std::vector<double>& x, std::size_t run, std::size_t block) const {
  const StatBlock& blk = stat_blocks_[run][block];
  const auto& t = runs_[run].time_s;
  double sw = 0, sum = 0, sq = 0;
  for (std::size_t i = blk.first; i < blk.end; ++i) {
    const double w = hann(t[i], blk);
    sw += w;
    sum += w * x[i];
  }
  const double mean = sum / sw;
  for (std::size_t i = blk.first; i < blk.end; ++i) sq += hann(t[i], blk) * (x[i] - mean) * (x[i] - mean);
  return {mean, std::sqrt(sq / sw)};
}

// Sum of squared residuals in noise units, and of squared residuals in signal units, of one
// channel over a set; the normalised entries are appended to `entries` when given.
std::pair<double, double> Engine::channel_sums(const Channel& c, const SampleSet& set,
                                               const Predictions& p, std::vector<double>* entries) const {
  double sn = 0, su = 0;
  const auto put = [&](double unit, double normalised) {
    su += unit * unit;
    sn += normalised * normalised;
    if (entries) entries->push_back(normalised);
  };
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    if (!p[k]) continue;
    const auto& m = measured(runs_[k], c.field);
    const auto& q = predicted(*p[k], c.field);
    if (!c.blocks) {
      for (std::size_t i : set.index[k]) put(q[i] - m[i], (q[i] - m[i]) / c.sigma);
      continue;
    }
    for (std::size_t b : set.blocks[k]) {
      const double n = stat_blocks_[k][b].n_eff;
      const BlockStats sm = stats(m, k, b), sq = stats(q, k, b);
      // The measured spread holds the sensor noise; remove it in quadrature.
      const double meas_std = std::sqrt(std::max(0.0, sm.std * sm.std - c.sigma * c.sigma));
      const double var = c.sigma * c.sigma / n;
      const BlockStats& jitter = block_jitter_var_[k];
      put(sq.mean - sm.mean, (sq.mean - sm.mean) / std::sqrt(var + 2.0 * jitter.mean));
      put(sq.std - meas_std, (sq.std - meas_std) / std::sqrt(0.5 * var + 2.0 * jitter.std));
    }
  }
  return {sn, su};
}

double Engine::misfit(const SampleSet& set, const Predictions& p) const {
  double j = 0;
  for (const auto& c : channels_) {
    std::vector<double> e;
    const double sn = channel_sums(c, set, p, &e).first;
    if (!e.empty()) j += channel_weight(c) * sn / static_cast<double>(e.size());
  }
  return j;
}

// Torque is the one mechanical signal; temp_C, sump_temp_C and ir_temp_C all watch the thermal
// state. Each side gets half of J, so an effect that only moves the torque (load dependence,
// bearing drag) is not outvoted by three thermometers that it leaves unchanged.
double Engine::channel_weight(const Channel& c) const {
  if (c.field == Field::kTorque) return 0.5;
  return 0.5 / static_cast<double>(channels_.size() - 1);
}

Misfit Engine::rms(const SampleSet& set, const Predictions& p) const {
  Misfit m;
  for (const auto& c : channels_) {
    if (c.field != Field::kTorque && c.field != Field::kTemp) continue;
    std::vector<double> e;
    const double su = channel_sums(c, set, p, &e).second;
    // Block channels put two entries (mean, spread) per block: rms per block of both.
    const double count = static_cast<double>(e.size()) / (c.blocks ? 2.0 : 1.0);
    const double v = e.empty() ? 0.0 : std::sqrt(su / count);
    (c.field == Field::kTorque ? m.torque_rms_Nm : m.temp_rms_C) = v;
  }
  return m;
}

bool Engine::residual_vector(const SampleSet& set, const Predictions& p, Eigen::VectorXd& out) const {
  // Scaled so that the sum of squares is the misfit J of the set.
  std::vector<double> all;
  for (const auto& c : channels_) {
    std::vector<double> e;
    channel_sums(c, set, p, &e);
    const double w = std::sqrt(channel_weight(c) / static_cast<double>(std::max<std::size_t>(1, e.size())));
    for (double x : e) all.push_back(w * x);
  }
  out = Eigen::Map<const Eigen::VectorXd>(all.data(), static_cast<Eigen::Index>(all.size()));
  return out.allFinite();
}

std::size_t Engine::residual_count(const SampleSet& set) const {
  std::size_t n = 0;
  for (const auto& c : channels_)
    for (std::size_t k = 0; k < runs_.size(); ++k)
      n += c.blocks ? 2 * set.blocks[k].size() : set.index[k].size();
  return n;
}

double Engine::channel_misfit(const Channel& c, const SampleSet& set, const Predictions& p) const {
  std::vector<double> e;
  const double sn = channel_sums(c, set, p, &e).first;
  return e.empty() ? 0.0 : sn / static_cast<double>(e.size());
}

void Engine::choose_channels() {
  const auto pooled_sigma = [&](Field f, double floor) {
    double v = 0, n = 0;
    for (const auto& run : runs_) {
      const double w = static_cast<double>(run.time_s.size());
      v += w * std::pow(estimate_noise_sigma(measured(run, f)), 2);
      n += w;
    }
    return std::max(std::sqrt(v / n), floor);
  };
  const auto every_run_has = [&](Field f) {
    for (const auto& run : runs_)
      if (measured(run, f).size() != run.time_s.size()) return false;
    return true;
  };
  channels_.clear();
  channels_.push_back({Field::kTorque, "torque_Nm", pooled_sigma(Field::kTorque, opt_.min_noise_torque_Nm),
                       opt_.torque_block_statistics});
  channels_.push_back({Field::kTemp, "temp_C", pooled_sigma(Field::kTemp, opt_.min_noise_temp_C), false});
  if (every_run_has(Field::kSump))
    channels_.push_back({Field::kSump, "sump_temp_C", pooled_sigma(Field::kSump, opt_.min_noise_temp_C), false});
  if (every_run_has(Field::kIr))
    channels_.push_back({Field::kIr, "ir_temp_C", pooled_sigma(Field::kIr, opt_.min_noise_temp_C), false});
  sigma_torque_ = channels_[0].sigma;
  sigma_temp_ = channels_[1].sigma;
}

std::vector<std::size_t> union_runs(const SampleSet& a, const SampleSet& b) {
  std::vector<std::size_t> r;
  for (std::size_t k = 0; k < a.index.size(); ++k)
    if (!a.index[k].empty() || !b.index[k].empty()) r.push_back(k);
  return r;
}

Engine::FlatConfig Engine::flatten(const Config& config) const {
  FlatConfig f{config, {}, {}, {}, {}};
  for (std::size_t e = 0; e < config.size(); ++e) {
    const auto& c = candidate(config[e].effect);
    for (std::size_t j = 0; j < config[e].values.size(); ++j) {
      f.slots.emplace_back(e, j);
      f.values.push_back(config[e].values[j]);
      f.lower.push_back(c.lower[j]);
      f.upper.push_back(c.upper[j]);
    }
  }
  return f;
}

Config Engine::FlatConfig::with(const std::vector<double>& v) const {
  Config out = config;
  for (std::size_t s = 0; s < slots.size(); ++s) out[slots[s].first].values[slots[s].second] = v[s];
  return out;
}

std::optional<Config> Engine::fit_config(const FlatConfig& flat, std::vector<std::vector<double>> starts,
                                         const SampleSet& set, unsigned jobs, int& evaluations) const {
  if (flat.slots.empty()) return flat.config;
  LogParameterProblem problem;
  problem.lower = flat.lower;
  problem.upper = flat.upper;
  problem.starts = std::move(starts);
  problem.residuals = static_cast<int>(residual_count(set));
  problem.max_evaluations = opt_.max_evaluations;
  const auto runs = set.runs();
  problem.evaluate = [&](const std::vector<double>& v, Eigen::VectorXd& r) {
    return residual_vector(set, simulate(flat.with(v), runs, jobs), r);
  };
  const LogParameterFit fit = fit_log_parameters(problem);
  evaluations += fit.evaluations;
  if (!fit.feasible) return std::nullopt;
  return flat.with(fit.values);
}

Engine::Outcome Engine::fit_candidate(const EffectCandidate& c, const Config& fold,
                                      const Predictions& current) const {
  Outcome o;
  o.score.effect = c.name;
  const std::size_t k = c.parameter_names.size();
  // The candidate is fitted together with the parameters of every effect added before it, so
  // an earlier effect that stood in for this one (a heat sink imitating oil cooling) can give
  // its share back instead of blocking it. Its starts follow the earlier effects' values.
  Config cfg = fold;
  cfg.push_back({c.name, k > 0 ? c.starts.front() : std::vector<double>{}});
  const FlatConfig flat = flatten(cfg);
  std::vector<std::vector<double>> starts;
  for (const auto& start : k > 0 ? c.starts : std::vector<std::vector<double>>{{}}) {
    starts.emplace_back(flat.values.begin(), flat.values.end() - static_cast<std::ptrdiff_t>(k));
    starts.back().insert(starts.back().end(), start.begin(), start.end());
  }
  try {
    const auto fitted = fit_config(flat, std::move(starts), fit_, 1, o.score.evaluations);
    if (!fitted) {
      o.score.failure = "no parameter values could be simulated";
      return o;
    }
    o.config = *fitted;
    o.predictions = simulate(o.config, union_runs(fit_, holdout_), 1);
    ++o.score.evaluations;
  } catch (const std::exception& e) {
    o.score.failure = e.what();
    return o;
  }
  for (std::size_t j = 0; j < k; ++j)
    o.score.parameters.emplace_back(c.parameter_names[j], o.config.back().values[j]);
  o.score.fit_misfit = misfit(fit_, o.predictions);
  o.score.holdout_misfit = misfit(holdout_, o.predictions);
  o.score.score = o.score.holdout_misfit + opt_.penalty_per_parameter * static_cast<double>(k);
  o.score.gain = misfit(holdout_, current) - o.score.score;
  o.score.signature_correlation = signature_correlation(current, o.predictions);
  o.ok = true;
  return o;
}

Config Engine::refit_all(const Config& full, const Config& fold_added, Predictions& out) const {
  // Joint refit of every added effect's parameters on all runs, from the current values.
  Config start = full;
  start.push_back(fold_added.back());
  const FlatConfig flat = flatten(start);
  int evaluations = 0;
  if (auto fitted = fit_config(flat, {flat.values}, all_, opt_.jobs, evaluations)) start = std::move(*fitted);
  const auto all_runs = all_.runs();
  out = simulate(start, all_runs, opt_.jobs);
  return start;
}

double Engine::signature_correlation(const Predictions& current, const Predictions& cand) const {
  // Does the change the effect makes look like the residual it should remove? Block means of
  // (candidate − current) against (measured − current), both signals in noise units.
  std::vector<double> change, target;
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    if (!current[k] || !cand[k]) continue;
    const auto& m = runs_[k];
    const auto blocks = residual_blocks(m.time_s);
    const auto add = [&](const std::vector<double>& meas, const std::vector<double>& cur,
                         const std::vector<double>& next, double sigma) {
      std::vector<double> d(meas.size()), t(meas.size());
      for (std::size_t i = 0; i < meas.size(); ++i) {
        d[i] = (next[i] - cur[i]) / sigma;
        t[i] = (meas[i] - cur[i]) / sigma;
      }
      const auto bd = block_means(d, blocks), bt = block_means(t, blocks);
      change.insert(change.end(), bd.begin(), bd.end());
      target.insert(target.end(), bt.begin(), bt.end());
    };
    add(m.torque_Nm, current[k]->torque_Nm, cand[k]->torque_Nm, sigma_torque_);
    add(m.temp_C, current[k]->temp_C, cand[k]->temp_C, sigma_temp_);
  }
  return pearson(change, target);
}

std::vector<std::pair<std::string, double>> Engine::pooled_tracking(const Predictions& p,
                                                                    bool torque) const {
  std::vector<double> residual;
  BlockFeatures pooled;
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    if (!p[k]) continue;
    const auto& m = runs_[k];
    const auto blocks = residual_blocks(m.time_s);
    const auto& model = torque ? p[k]->torque_Nm : p[k]->temp_C;
    const auto& meas = torque ? m.torque_Nm : m.temp_C;
    std::vector<double> r(meas.size());
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = model[i] - meas[i];
    const auto rb = block_means(r, blocks);
    residual.insert(residual.end(), rb.begin(), rb.end());
    const auto f = block_features(m.time_s, m.speed_rpm, m.temp_C, m.normal_force_N, blocks);
    if (pooled.names.empty()) {
      pooled.names = f.names;
      pooled.values.assign(f.names.size(), {});
    }
    for (std::size_t j = 0; j < f.names.size(); ++j)
      pooled.values[j].insert(pooled.values[j].end(), f.values[j].begin(), f.values[j].end());
  }
  return rank_features(residual, pooled);
}

std::vector<Disagreement> Engine::disagreements(const Predictions& p) const {
  std::vector<Disagreement> out;
  for (const bool torque : {true, false}) {
    const auto ranked = pooled_tracking(p, torque);
    const double sigma = torque ? sigma_torque_ : sigma_temp_;
    for (std::size_t k = 0; k < runs_.size(); ++k) {
      const auto& m = runs_[k];
      const auto& model = torque ? p[k]->torque_Nm : p[k]->temp_C;
      const auto& meas = torque ? m.torque_Nm : m.temp_C;
      std::vector<double> r(meas.size());
      for (std::size_t i = 0; i < r.size(); ++i) r[i] = model[i] - meas[i];
      for (const auto& s : residual_segments(r, sigma, residual_blocks(m.time_s))) {
        Disagreement d;
        d.run = m.name;
        d.signal = torque ? "torque_Nm" : "temp_C";
        d.t_start_s = m.time_s[s.first_sample];
        d.t_end_s = m.time_s[s.end_sample - 1];
        d.mean_error = s.mean;
        if (!ranked.empty()) {
          d.tracks = ranked.front().first;
          d.correlation = ranked.front().second;
        }
        out.push_back(d);
      }
    }
  }
  return out;
}

std::vector<Tracking> Engine::tracking(const Predictions& p) const {
  std::vector<Tracking> out;
  for (const bool torque : {true, false}) {
    const std::string signal = torque ? "torque_Nm" : "temp_C";
    if (runs_.size() > 1) out.push_back({"all runs", signal, pooled_tracking(p, torque)});
    for (std::size_t k = 0; k < runs_.size(); ++k) {
      Predictions one(runs_.size());
      one[k] = p[k];
      out.push_back({runs_[k].name, signal, pooled_tracking(one, torque)});
    }
  }
  return out;
}

const EffectCandidate& Engine::candidate(const std::string& name) const {
  for (const auto& c : candidates_)
    if (c.name == name) return c;
  throw std::logic_error("unknown candidate " + name);
}

std::string Engine::reason(const DiagnosisStep& step, const Predictions& current) const {
  const auto& best = step.candidates.front();
  std::ostringstream os;
  const auto& c = candidate(step.effect);
  os << step.effect;
  if (!c.description.empty()) os << " (" << c.description << ")";
  os << ": ";
  const auto torque = pooled_tracking(current, true), temp = pooled_tracking(current, false);
  const auto tr = [](const std::vector<std::pair<std::string, double>>& r) {
    return r.empty() ? std::string("nothing") : r.front().first + " (" + fmt(r.front().second, "%.2f") + ")";
  };
  os << "before it, the torque error tracked " << tr(torque) << " and the temperature error "
     << tr(temp) << ". The change this effect makes matches that residual (signature r = "
     << fmt(best.signature_correlation, "%.2f") << ")";
  if (!step.parameters.empty()) {
    os << " with ";
    for (std::size_t j = 0; j < step.parameters.size(); ++j)
      os << (j ? ", " : "") << step.parameters[j].first << " = " << fmt(step.parameters[j].second, "%.4g");
  }
  os << ", and it lowers the held-out misfit from " << fmt(step.holdout_misfit_before) << " to "
     << fmt(step.holdout_misfit_after) << " (1 = noise level)";
  if (step.candidates.size() > 1) {
    const auto& next = step.candidates[1];
    os << "; the next best, " << next.effect << ", reached " << fmt(next.holdout_misfit);
  }
  os << ".";
  return os.str();
}

DiagnosisResult Engine::run() {
  const auto wall0 = Clock::now();
  check_inputs();
  DiagnosisResult r;
  for (const auto& run : runs_) r.runs.push_back(run.name);

  choose_channels();
  r.noise_torque_Nm = sigma_torque_;
  r.noise_temp_C = sigma_temp_;
  build_sample_sets(r);
  estimate_block_jitter(channels_.front());

  Config fold, full;
  const Predictions baseline = simulate({}, all_.runs(), opt_.jobs);
  Predictions fold_pred = baseline, full_pred = baseline;
  r.baseline = rms(all_, baseline);
  r.baseline_holdout_misfit = misfit(holdout_, baseline);
  r.disagreements = disagreements(baseline);
  r.tracking = tracking(baseline);

  std::string stop;
  for (int round = 0;; ++round) {
    bool within = true;
    std::string levels;
    for (const auto& c : channels_) {
      const double j = channel_misfit(c, all_, full_pred);
      within = within && j <= opt_.noise_tolerance * opt_.noise_tolerance;
      levels += (levels.empty() ? "" : ", ") + c.name + " " + fmt(std::sqrt(j), "%.2f");
    }
    if (within) {
      stop = "every signal is within " + fmt(opt_.noise_tolerance, "%.2g") +
             " x its noise (rms / noise: " + levels + ")";
      break;
    }
    if (round >= opt_.max_effects) {
      stop = "the limit of " + std::to_string(opt_.max_effects) + " added effects was reached";
      break;
    }
    std::vector<const EffectCandidate*> open;
    for (const auto& c : candidates_) {
      bool added = false;
      for (const auto& s : fold) added = added || s.effect == c.name;
      if (!added) open.push_back(&c);
    }
    if (open.empty()) {
      stop = "every candidate effect has been added";
      break;
    }
    // Longest fits first (most parameters: most evaluations), so that no long fit starts last
    // and leaves the other threads idle at the end of the round.
    std::stable_sort(open.begin(), open.end(), [](const EffectCandidate* a, const EffectCandidate* b) {
      return a->parameter_names.size() > b->parameter_names.size();
    });
    std::vector<Outcome> outcomes(open.size());
    parallel_for(open.size(), opt_.jobs,
                 [&](std::size_t i) { outcomes[i] = fit_candidate(*open[i], fold, fold_pred); });
    std::stable_sort(outcomes.begin(), outcomes.end(), [](const Outcome& a, const Outcome& b) {
      if (a.ok != b.ok) return a.ok;
      return a.score.score < b.score.score;
    });
    std::vector<CandidateScore> scores;
    for (const auto& o : outcomes) scores.push_back(o.score);
    const Outcome& best = outcomes.front();
    const double k = static_cast<double>(best.score.parameters.size());
    if (!best.ok || best.score.gain < opt_.min_gain) {
      r.last_round = scores;
      stop = best.ok ? "no candidate lowers the held-out misfit by more than " +
                           fmt(opt_.min_gain + opt_.penalty_per_parameter * k) +
                           " (best: " + best.score.effect + ", gain " + fmt(best.score.gain) + ")"
                     : "no candidate could be fitted";
      break;
    }
    DiagnosisStep step;
    step.effect = best.score.effect;
    step.candidates = scores;
    step.holdout_misfit_before = misfit(holdout_, fold_pred);
    step.holdout_misfit_after = best.score.holdout_misfit;
    step.holdout = rms(holdout_, best.predictions);
    const Predictions before = full_pred;
    fold = best.config;
    for (std::size_t kk = 0; kk < runs_.size(); ++kk)
      if (best.predictions[kk]) fold_pred[kk] = best.predictions[kk];
    full = refit_all(full, fold, full_pred);
    const auto& c = candidate(step.effect);
    for (std::size_t j = 0; j < c.parameter_names.size(); ++j)
      step.parameters.emplace_back(c.parameter_names[j], full.back().values[j]);
    step.misfit = rms(all_, full_pred);
    step.reason = reason(step, before);
    r.missing_effects.push_back(step.effect);
    r.steps.push_back(std::move(step));
  }

  r.final = rms(all_, full_pred);
  for (const auto& e : full) {
    FittedEffect f{e.effect, {}};
    const auto& c = candidate(e.effect);
    for (std::size_t j = 0; j < e.values.size(); ++j) f.parameters.emplace_back(c.parameter_names[j], e.values[j]);
    r.final_effects.push_back(std::move(f));
  }
  for (const auto& c : channels_) {
    ChannelFit f;
    f.signal = c.name;
    f.comparison = c.blocks ? "block_statistics" : "pointwise";
    f.noise = c.sigma;
    std::vector<double> e;
    const double baseline_sq = channel_sums(c, all_, baseline, &e).second;
    // Block channels put two entries (mean, spread) per block: rms per block of both.
    const double count = static_cast<double>(e.size()) / (c.blocks ? 2.0 : 1.0);
    f.baseline_rms = std::sqrt(baseline_sq / count);
    f.final_rms = std::sqrt(channel_sums(c, all_, full_pred, nullptr).second / count);
    f.baseline_misfit = channel_misfit(c, all_, baseline);
    f.final_misfit = channel_misfit(c, all_, full_pred);
    r.channels.push_back(f);
  }
  r.final_holdout_misfit = misfit(holdout_, fold_pred);
  r.final_disagreements = disagreements(full_pred);
  std::ostringstream concl;
  if (r.missing_effects.empty()) {
    concl << "Nothing is missing that the candidates could explain: " << stop << ".";
  } else {
    concl << "Missing: ";
    for (std::size_t i = 0; i < r.missing_effects.size(); ++i)
      concl << (i ? ", then " : "") << r.missing_effects[i];
    concl << ". Torque RMS " << fmt(r.baseline.torque_rms_Nm) << " -> " << fmt(r.final.torque_rms_Nm)
          << " Nm, temperature RMS " << fmt(r.baseline.temp_rms_C) << " -> " << fmt(r.final.temp_rms_C)
          << " C (noise " << fmt(sigma_torque_) << " Nm, " << fmt(sigma_temp_)
          << " C). The search stopped because " << stop << ".";
  }
  r.conclusion = concl.str();

  for (std::size_t k = 0; k < runs_.size(); ++k) {
    RunTraces t;
    t.run = runs_[k].name;
    for (std::size_t i : all_.index[k]) {
      t.time_s.push_back(runs_[k].time_s[i]);
      t.torque_measured.push_back(runs_[k].torque_Nm[i]);
      t.torque_baseline.push_back(baseline[k]->torque_Nm[i]);
      t.torque_final.push_back(full_pred[k]->torque_Nm[i]);
      t.temp_measured.push_back(runs_[k].temp_C[i]);
      t.temp_baseline.push_back(baseline[k]->temp_C[i]);
      t.temp_final.push_back(full_pred[k]->temp_C[i]);
    }
    r.traces.push_back(std::move(t));
  }
  r.simulations = simulations_;
  r.simulation_thread_s = sim_thread_s_;
  r.wall_s = seconds_since(wall0);
  return r;
}

}  // namespace

DiagnosisResult diagnose(const std::vector<DiagnosisRun>& runs,
                         const std::vector<EffectCandidate>& candidates, const Simulator& simulate,
                         const DiagnosisOptions& options) {
  // Process CPU time over all threads; the simulations' share is timed inside the engine.
  const std::clock_t cpu0 = std::clock();
  Engine engine(runs, candidates, simulate, options);
  DiagnosisResult r = engine.run();
  const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  r.fitting_thread_s = std::max(0.0, cpu_s - r.simulation_thread_s);
  return r;
}

}  // namespace shudder::analysis
