#pragma once
// The misfit of a model's predictions against measured runs, over named channels
// (analysis/diagnosis.hpp has the method; docs/diagnosis.md the reasoning):
//
//   channels   torque_Nm, temp_C always; sump_temp_C and ir_temp_C when every run has them.
//              Each has a noise sigma pooled over the runs (analysis/noise_estimate.hpp).
//              With a model-form tolerance on the temperatures and an IR spot in every run,
//              also temp_minus_ir_C: the thermocouple less the IR spot, sample by sample,
//              without temp_C's tolerance (choose_channels says why).
//   J          = ½ J_torque + ½ mean of J_c over the temperature channels, J_c = mean((r/σ)²)
//              over a sample set, r = model − measured. J ≈ 1 at the noise.
//   blocks     torque compared by block statistics (DiagnosisOptions::torque_block_statistics):
//              Hann-weighted mean and spread over blocks of statistics_block_s every half block;
//              error scale = sensor noise over the block plus the block-to-block jitter the
//              measured statistics show beyond it, for model and measurement both.
//   scale      the error scale of one comparison: sensor noise (and, for blocks, jitter) plus,
//              in quadrature, the replay's reproduction error (set_reproduction) and the user's
//              model-form tolerance of the channel (DiagnosisOptions::tolerance).
//   sets       all samples (every k-th beyond max_samples_per_run), the fit set and the
//              hold-out: the last run with several runs, odd tenths of the time with one.

#include <Eigen/Dense>
#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/diagnosis.hpp"

namespace shudder::analysis {

/// Per run: the prediction at the fitted values, empty where the run was not simulated.
using Predictions = std::vector<std::optional<Prediction>>;

enum class Signal { kTorque, kTemp, kSump, kIr, kTempMinusIr };
/// A stored column; std::logic_error for kTempMinusIr, which has none (use *_values).
const std::vector<double>& measured(const DiagnosisRun& r, Signal s);
const std::vector<double>& predicted(const Prediction& p, Signal s);

/// One channel's values in a run or prediction: a stored column, or for kTempMinusIr the
/// thermocouple less the IR spot, sample by sample.
class SignalValues {
 public:
  explicit SignalValues(const std::vector<double>& a, const std::vector<double>* minus = nullptr)
      : a_(&a), minus_(minus) {}
  double operator[](std::size_t i) const { return minus_ ? (*a_)[i] - (*minus_)[i] : (*a_)[i]; }
  std::size_t size() const { return minus_ ? std::min(a_->size(), minus_->size()) : a_->size(); }

 private:
  const std::vector<double>* a_;
  const std::vector<double>* minus_;
};
SignalValues measured_values(const DiagnosisRun& r, Signal s);
SignalValues predicted_values(const Prediction& p, Signal s);

struct Channel {
  Signal signal;
  std::string name;
  double sigma = 0.0;      // noise of one sample
  bool blocks = false;     // compared by block statistics
  double tolerance = 0.0;  // model-form tolerance (signal unit), DiagnosisOptions::tolerance
};

/// Sample indices and statistics blocks per run (empty for a run outside the set).
struct SampleSet {
  std::vector<std::vector<std::size_t>> index;
  std::vector<std::vector<std::size_t>> blocks;  // indices into the run's statistics blocks
  std::size_t size() const;
  std::vector<std::size_t> runs() const;  // runs with samples in the set
};

/// Runs with samples in either set.
std::vector<std::size_t> union_runs(const SampleSet& a, const SampleSet& b);

class MisfitModel {
 public:
  /// Chooses the channels, estimates their noise, builds the sample sets. Throws
  /// std::invalid_argument if a single run is too short to split into fit and hold-out.
  MisfitModel(const std::vector<DiagnosisRun>& runs, const DiagnosisOptions& options);

  const std::vector<Channel>& channels() const { return channels_; }
  const SampleSet& all() const { return all_; }
  const SampleSet& fit() const { return fit_; }
  const SampleSet& holdout() const { return holdout_; }
  const HoldoutSplit& holdout_split() const { return split_; }

  /// J over a set.
  double misfit(const SampleSet& set, const Predictions& p) const;
  /// J_c of one channel over a set.
  double channel_misfit(const Channel& c, const SampleSet& set, const Predictions& p) const;
  /// RMS of model − measured of one channel (block channels: per block of both statistics).
  double channel_rms(const Channel& c, const SampleSet& set, const Predictions& p) const;
  /// Torque and temp_C RMS over a set.
  Misfit rms(const SampleSet& set, const Predictions& p) const;
  /// The replay's reproduction error: `truth` are the baseline's predictions, `replayed` the
  /// replays of those predictions taken as measured runs (noise added). Their differences,
  /// compared as the channel compares (pointwise or block statistics), join every later error
  /// scale in quadrature, per run.
  void set_reproduction(const Predictions& truth, const Predictions& replayed);
  /// RMS over all runs of the reproduction error of one channel (signal unit; 0 if not set).
  double reproduction_rms(const Channel& c) const;
  /// RMS of the error scale of one channel over a set (signal unit): what "within" is measured
  /// against (J_c = 1 when the residuals are as large as it).
  double channel_scale(const Channel& c, const SampleSet& set) const;
  /// A pointwise scale of one channel for segment detection: noise, reproduction and
  /// tolerance in quadrature (block channels: the sensor noise part of it).
  double pointwise_scale(const Channel& c) const;
  /// Residuals scaled so that their sum of squares is J; false if any is not finite.
  bool residual_vector(const SampleSet& set, const Predictions& p, Eigen::VectorXd& out) const;
  std::size_t residual_count(const SampleSet& set) const;

 private:
  struct BlockStats {
    double mean = 0.0, std = 0.0;
  };
  // A statistics block: samples [first, end) weighted by a Hann window over [t0_s, t0_s + length_s].
  struct StatBlock {
    std::size_t first, end;
    double t0_s, length_s;
    double n_eff;  // (Σw)² / Σw²: the sample count whose plain mean has the same noise
  };
  static double hann(double t_s, const StatBlock& b);
  BlockStats stats(const std::vector<double>& x, std::size_t run, std::size_t block) const;
  struct Sums {
    double normalised = 0.0, unit = 0.0, scale2 = 0.0;  // Σ (r/s)², Σ r², Σ s²
  };
  Sums channel_sums(const Channel& c, const SampleSet& set, const Predictions& p, std::vector<double>* entries) const;
  std::size_t channel_index(const Channel& c) const;
  double channel_weight(const Channel& c) const;
  void choose_channels();
  void build_sample_sets();
  void estimate_block_jitter(const Channel& c);

  const std::vector<DiagnosisRun>& runs_;
  const DiagnosisOptions& opt_;
  std::vector<Channel> channels_;
  std::vector<std::vector<StatBlock>> stat_blocks_;  // per run
  // Per run: variance of the block mean and block spread beyond what sensor noise explains.
  std::vector<BlockStats> block_jitter_var_;
  // Per channel and run: reproduction error variance (pointwise: in .mean; blocks: of the
  // block mean and spread).
  std::vector<std::vector<BlockStats>> reproduction_var_;
  SampleSet all_, fit_, holdout_;
  HoldoutSplit split_;
};

}  // namespace shudder::analysis
