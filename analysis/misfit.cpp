#include "analysis/misfit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "analysis/noise_estimate.hpp"

namespace shudder::analysis {

std::size_t SampleSet::size() const {
  std::size_t n = 0;
  for (const auto& i : index) n += i.size();
  return n;
}

std::vector<std::size_t> SampleSet::runs() const {
  std::vector<std::size_t> r;
  for (std::size_t k = 0; k < index.size(); ++k)
    if (!index[k].empty()) r.push_back(k);
  return r;
}

MisfitModel::MisfitModel(const std::vector<DiagnosisRun>& runs, const DiagnosisOptions& options)
    : runs_(runs), opt_(options) {
  choose_channels();
  build_sample_sets();
  estimate_block_jitter(channels_.front());
}

double MisfitModel::channel_rms(const Channel& c, const SampleSet& set, const Predictions& p) const {
  std::vector<double> e;
  const double sq = channel_sums(c, set, p, &e).unit;
  // Block channels put two entries (mean, spread) per block: rms per block of both.
  const double count = static_cast<double>(e.size()) / (c.blocks ? 2.0 : 1.0);
  return std::sqrt(sq / count);
}

// The block statistics of a steady signal scatter by the sensor noise alone (σ²/n); a cycle
// that is not a whole number of times in a block adds a jitter that model and measurement
// each have (hence the factor 2 where it is used). Its size is read off the measured
// statistics with the same second-difference estimator as the sensor noise (trends and
// single kinks drop out), less the noise part. Fewer than 5 blocks: no estimate, noise only.
void MisfitModel::estimate_block_jitter(const Channel& c) {
  block_jitter_var_.assign(runs_.size(), {});
  if (!c.blocks) return;
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    const std::size_t nb = stat_blocks_[k].size();
    if (nb < 5) continue;
    std::vector<double> means, spreads;
    double noise_var = 0;
    for (std::size_t b = 0; b < nb; ++b) {
      const BlockStats s = stats(measured(runs_[k], c.signal), k, b);
      means.push_back(s.mean);
      spreads.push_back(s.std);
      noise_var += c.sigma * c.sigma / stat_blocks_[k][b].n_eff / static_cast<double>(nb);
    }
    block_jitter_var_[k] = {std::max(0.0, std::pow(estimate_noise_sigma(means), 2) - noise_var),
                            std::max(0.0, std::pow(estimate_noise_sigma(spreads), 2) - 0.5 * noise_var)};
  }
}

void MisfitModel::build_sample_sets() {
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
    for (double t0 = t.front(); t0 + length <= t.back() + 1e-9 * length; t0 += 0.5 * length) starts.push_back(t0);
    if (starts.empty() || starts.back() + length < t.back() - 0.25 * length) starts.push_back(t.back() - length);
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
    split_ = {HoldoutSplit::Kind::kLastRun, runs_.back().name};
    return;
  }
  // One run: alternate tenths of its duration; hold out the odd ones.
  const auto& t = runs_[0].time_s;
  const double tenth = (t.back() - t.front()) / 10.0;
  const auto odd = [&](double time) { return std::min(9, static_cast<int>((time - t.front()) / tenth)) % 2 == 1; };
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
  split_ = {HoldoutSplit::Kind::kOddTenths, {}};
}

const std::vector<double>& measured(const DiagnosisRun& r, Signal f) {
  switch (f) {
    case Signal::kTorque: return r.torque_Nm;
    case Signal::kTemp: return r.temp_C;
    case Signal::kSump: return r.sump_temp_C;
    case Signal::kIr: return r.ir_temp_C;
    case Signal::kTempMinusIr: break;
  }
  throw std::logic_error("temp_minus_ir_C is derived, not a stored column");
}

const std::vector<double>& predicted(const Prediction& p, Signal f) {
  switch (f) {
    case Signal::kTorque: return p.torque_Nm;
    case Signal::kTemp: return p.temp_C;
    case Signal::kSump: return p.sump_temp_C;
    case Signal::kIr: return p.ir_temp_C;
    case Signal::kTempMinusIr: break;
  }
  throw std::logic_error("temp_minus_ir_C is derived, not a stored column");
}

SignalValues measured_values(const DiagnosisRun& r, Signal f) {
  return f == Signal::kTempMinusIr ? SignalValues(r.temp_C, &r.ir_temp_C) : SignalValues(measured(r, f));
}

SignalValues predicted_values(const Prediction& p, Signal f) {
  return f == Signal::kTempMinusIr ? SignalValues(p.temp_C, &p.ir_temp_C) : SignalValues(predicted(p, f));
}

// A Hann window keeps a cycle that does not fit a whole number of times into the block out of
// its mean and spread (leakage falls as 1/(cycles per block)³ instead of 1/cycles).
double MisfitModel::hann(double t_s, const StatBlock& b) {
  const double s = std::sin(std::numbers::pi * (t_s - b.t0_s) / b.length_s);
  return s * s;
}

MisfitModel::BlockStats MisfitModel::stats(const std::vector<double>& x, std::size_t run, std::size_t block) const {
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

// Sums of squared residuals in error-scale units and in signal units, and of the squared
// scales, of one channel over a set; the normalised entries are appended to `entries` when given.
MisfitModel::Sums MisfitModel::channel_sums(const Channel& c, const SampleSet& set, const Predictions& p,
                                            std::vector<double>* entries) const {
  Sums s;
  const auto put = [&](double unit, double scale2) {
    s.unit += unit * unit;
    s.normalised += unit * unit / scale2;
    s.scale2 += scale2;
    if (entries) entries->push_back(unit / std::sqrt(scale2));
  };
  const std::size_t ci = channel_index(c);
  const double tol2 = c.tolerance * c.tolerance;
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    if (!p[k]) continue;
    const BlockStats repro = reproduction_var_.empty() ? BlockStats{} : reproduction_var_[ci][k];
    if (!c.blocks) {
      const SignalValues m = measured_values(runs_[k], c.signal), q = predicted_values(*p[k], c.signal);
      const double scale2 = c.sigma * c.sigma + repro.mean + tol2;
      for (std::size_t i : set.index[k]) put(q[i] - m[i], scale2);
      continue;
    }
    const auto& m = measured(runs_[k], c.signal);
    const auto& q = predicted(*p[k], c.signal);
    for (std::size_t b : set.blocks[k]) {
      const double n = stat_blocks_[k][b].n_eff;
      const BlockStats sm = stats(m, k, b), sq = stats(q, k, b);
      // The measured spread holds the sensor noise; remove it in quadrature.
      const double meas_std = std::sqrt(std::max(0.0, sm.std * sm.std - c.sigma * c.sigma));
      const double var = c.sigma * c.sigma / n;
      const BlockStats& jitter = block_jitter_var_[k];
      put(sq.mean - sm.mean, var + 2.0 * jitter.mean + repro.mean + tol2);
      put(sq.std - meas_std, 0.5 * var + 2.0 * jitter.std + repro.std + tol2);
    }
  }
  return s;
}

std::size_t MisfitModel::channel_index(const Channel& c) const {
  for (std::size_t i = 0; i < channels_.size(); ++i)
    if (channels_[i].signal == c.signal) return i;
  return 0;
}

// The truth is known here (the baseline made it), so whatever the replay gets wrong is the
// replay's own: set point recovered from noisy signals, inputs averaged over windows, the
// start temperature read off a noisy thermometer. Compared exactly as the data are compared.
void MisfitModel::set_reproduction(const Predictions& truth, const Predictions& replayed) {
  reproduction_var_.assign(channels_.size(), std::vector<BlockStats>(runs_.size()));
  for (std::size_t ci = 0; ci < channels_.size(); ++ci) {
    const Channel& c = channels_[ci];
    for (std::size_t k = 0; k < runs_.size(); ++k) {
      if (!truth[k] || !replayed[k]) continue;
      BlockStats& v = reproduction_var_[ci][k];
      if (!c.blocks) {
        const SignalValues a = predicted_values(*truth[k], c.signal), b = predicted_values(*replayed[k], c.signal);
        if (a.size() != b.size() || a.size() == 0) continue;
        for (std::size_t i : all_.index[k]) v.mean += (b[i] - a[i]) * (b[i] - a[i]);
        v.mean /= static_cast<double>(std::max<std::size_t>(1, all_.index[k].size()));
        continue;
      }
      const auto& a = predicted(*truth[k], c.signal);
      const auto& b = predicted(*replayed[k], c.signal);
      if (a.size() != b.size() || a.empty()) continue;
      for (std::size_t blk : all_.blocks[k]) {
        const BlockStats sa = stats(a, k, blk), sb = stats(b, k, blk);
        v.mean += (sb.mean - sa.mean) * (sb.mean - sa.mean);
        v.std += (sb.std - sa.std) * (sb.std - sa.std);
      }
      const double nb = static_cast<double>(std::max<std::size_t>(1, all_.blocks[k].size()));
      v.mean /= nb;
      v.std /= nb;
    }
  }
}

double MisfitModel::reproduction_rms(const Channel& c) const {
  if (reproduction_var_.empty()) return 0.0;
  double v = 0;
  for (const auto& r : reproduction_var_[channel_index(c)]) v += c.blocks ? r.mean + r.std : r.mean;
  return std::sqrt(v / static_cast<double>(runs_.size()));
}

double MisfitModel::channel_scale(const Channel& c, const SampleSet& set) const {
  // The scales do not depend on the prediction; the measured run stands in for it.
  Predictions self(runs_.size());
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    Prediction p;
    p.torque_Nm = runs_[k].torque_Nm;
    p.temp_C = runs_[k].temp_C;
    p.sump_temp_C = runs_[k].sump_temp_C;
    p.ir_temp_C = runs_[k].ir_temp_C;
    self[k] = std::move(p);
  }
  std::vector<double> e;
  const double s2 = channel_sums(c, set, self, &e).scale2;
  return e.empty() ? 0.0 : std::sqrt(s2 / static_cast<double>(e.size()));
}

double MisfitModel::pointwise_scale(const Channel& c) const {
  double repro = 0;
  if (!reproduction_var_.empty() && !c.blocks) {
    for (const auto& r : reproduction_var_[channel_index(c)]) repro += r.mean;
    repro /= static_cast<double>(runs_.size());
  }
  return std::sqrt(c.sigma * c.sigma + repro + c.tolerance * c.tolerance);
}

// A channel with a model-form tolerance counts no lower than J_c = 1. The tolerance says the
// trusted model misses that channel by this much with nothing missing (docs/diagnosis.md
// "Choosing a tolerance": J_c ≈ 1 on the reference), so a model that comes closer is fitting
// the other model's form, not an effect: without the floor a candidate that also shaved the
// tolerated gap outscored the true one (tools/independent_sim: a small rig mass, 26 J/K, beside
// a 0.5 s sensor lag). The fit's residuals (residual_vector) are not floored.
double MisfitModel::misfit(const SampleSet& set, const Predictions& p) const {
  double j = 0;
  for (const auto& c : channels_) {
    std::vector<double> e;
    const double sn = channel_sums(c, set, p, &e).normalised;
    if (e.empty()) continue;
    const double jc = sn / static_cast<double>(e.size());
    j += channel_weight(c) * (c.tolerance > 0 ? std::max(jc, 1.0) : jc);
  }
  return j;
}

// Torque is the one mechanical signal; temp_C, sump_temp_C and ir_temp_C all watch the thermal
// state. Each side gets half of J, so an effect that only moves the torque (load dependence,
// bearing drag) is not outvoted by three thermometers that it leaves unchanged.
double MisfitModel::channel_weight(const Channel& c) const {
  if (c.signal == Signal::kTorque) return 0.5;
  return 0.5 / static_cast<double>(channels_.size() - 1);
}

Misfit MisfitModel::rms(const SampleSet& set, const Predictions& p) const {
  Misfit m;
  for (const auto& c : channels_) {
    if (c.signal != Signal::kTorque && c.signal != Signal::kTemp) continue;
    std::vector<double> e;
    const double su = channel_sums(c, set, p, &e).unit;
    // Block channels put two entries (mean, spread) per block: rms per block of both.
    const double count = static_cast<double>(e.size()) / (c.blocks ? 2.0 : 1.0);
    const double v = e.empty() ? 0.0 : std::sqrt(su / count);
    (c.signal == Signal::kTorque ? m.torque_rms_Nm : m.temp_rms_C) = v;
  }
  return m;
}

bool MisfitModel::residual_vector(const SampleSet& set, const Predictions& p, Eigen::VectorXd& out) const {
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

std::size_t MisfitModel::residual_count(const SampleSet& set) const {
  std::size_t n = 0;
  for (const auto& c : channels_)
    for (std::size_t k = 0; k < runs_.size(); ++k) n += c.blocks ? 2 * set.blocks[k].size() : set.index[k].size();
  return n;
}

double MisfitModel::channel_misfit(const Channel& c, const SampleSet& set, const Predictions& p) const {
  std::vector<double> e;
  const double sn = channel_sums(c, set, p, &e).normalised;
  return e.empty() ? 0.0 : sn / static_cast<double>(e.size());
}

void MisfitModel::choose_channels() {
  const auto pooled_sigma = [&](Signal f, double floor) {
    std::vector<const std::vector<double>*> signals;
    for (const auto& run : runs_) signals.push_back(&measured(run, f));
    return pooled_noise_sigma(signals, floor);
  };
  const auto every_run_has = [&](Signal f) {
    for (const auto& run : runs_)
      if (measured(run, f).size() != run.time_s.size()) return false;
    return true;
  };
  channels_.clear();
  channels_.push_back({Signal::kTorque, "torque_Nm", pooled_sigma(Signal::kTorque, opt_.min_noise_torque_Nm),
                       opt_.torque_block_statistics});
  channels_.push_back({Signal::kTemp, "temp_C", pooled_sigma(Signal::kTemp, opt_.min_noise_temp_C), false});
  if (every_run_has(Signal::kSump))
    channels_.push_back({Signal::kSump, "sump_temp_C", pooled_sigma(Signal::kSump, opt_.min_noise_temp_C), false});
  if (every_run_has(Signal::kIr))
    channels_.push_back({Signal::kIr, "ir_temp_C", pooled_sigma(Signal::kIr, opt_.min_noise_temp_C), false});
  // The thermocouple against the IR spot, when a tolerance says the data come from another
  // model or a real rig. Both thermometers watch the same interface a fraction of a millimetre
  // apart, so a model-form error of the heat balance (oil flow, grid, rig heat paths) moves
  // them together and cancels in their difference (measured on tools/independent_sim's runs:
  // 0.08 °C RMS of a 1.3 °C gap), while the thermocouple's own faults stay in it (a 1 s lag:
  // 1.4 °C RMS; an offset: the offset). So the difference is judged against its noise alone,
  // not temp_C's tolerance: a sensor fault as large as the tolerance stays visible. Without a
  // tolerance temp_C and ir_temp_C are each judged against their noise, and their difference
  // would add no evidence, only weight.
  bool temperature_tolerance = false;
  for (const auto& [name, tol] : opt_.tolerance)
    temperature_tolerance = temperature_tolerance || ((name == "temp_C" || name == "ir_temp_C") && tol > 0);
  if (temperature_tolerance && every_run_has(Signal::kIr)) {
    std::vector<std::vector<double>> differences;
    for (const auto& run : runs_) {
      std::vector<double> d(run.temp_C.size());
      for (std::size_t i = 0; i < d.size(); ++i) d[i] = run.temp_C[i] - run.ir_temp_C[i];
      differences.push_back(std::move(d));
    }
    std::vector<const std::vector<double>*> signals;
    for (const auto& d : differences) signals.push_back(&d);
    channels_.push_back(
        {Signal::kTempMinusIr, "temp_minus_ir_C", pooled_noise_sigma(signals, opt_.min_noise_temp_C), false});
  }
  // temp_C's tolerance also serves the other thermometers unless they have their own: they
  // watch the same thermal model, whose form error they share (not their difference, above).
  for (auto& c : channels_) {
    for (const auto& [name, tol] : opt_.tolerance)
      if (name == "temp_C" && c.signal != Signal::kTorque && c.signal != Signal::kTempMinusIr) c.tolerance = tol;
    for (const auto& [name, tol] : opt_.tolerance)
      if (name == c.name) c.tolerance = tol;
  }
}

std::vector<std::size_t> union_runs(const SampleSet& a, const SampleSet& b) {
  std::vector<std::size_t> r;
  for (std::size_t k = 0; k < a.index.size(); ++k)
    if (!a.index[k].empty() || !b.index[k].empty()) r.push_back(k);
  return r;
}

}  // namespace shudder::analysis
