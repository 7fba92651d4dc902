#pragma once
// Fitting one candidate effect (analysis/diagnosis.hpp, "fitting"): the candidate's log
// parameters together with those of every effect added before it, by Levenberg–Marquardt over
// several starts (analysis/log_parameter_fit.hpp) on the fit set, then scored on the hold-out:
//
//   score = J_holdout + penalty · (its parameters) · s,  s = max(1, J_ref)
//   gain  = J_ref − score, J_ref the hold-out misfit of the earlier effects refitted alone
//   signature r = Pearson r of block means of (candidate − current) and (measured − current),
//                 torque and temp_C in noise units: does the change look like the residual?

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "analysis/misfit.hpp"

namespace shudder::analysis {

/// The effects added to the baseline, each with its parameter values.
using Config = std::vector<EffectSetting>;

/// The acceptance threshold of the greedy search and its backward check: the held-out misfit
/// drop a unit of `members` effects (one, or a joint step's pair) with `parameters` fitted
/// parameters in all must show to be added, and that taking it out again must cost for it to
/// stay (effect_selection.cpp):
///
///   needed = (min_gain · members + penalty_per_parameter · parameters) · s,  s = max(1, J_ref)
///
/// Derivation (docs/diagnosis.md "Fair selection", "Joint step"): an effect must gain min_gain
/// on its own, since less is what any flexible term shaves off a systematic gap; that share
/// grows with the gap, hence × s (at the noise, J ≈ 1, the threshold is absolute). Each free
/// parameter buys some fit of anything (the AIC idea), so it pays penalty_per_parameter on top.
/// A pair counts as two effects, each paying its own min_gain, and only the parameters it fits.
/// A candidate's score carries all of this but one min_gain · s (needed_gain(o, members − 1,
/// parameters, s)), which its gain J_ref − score must then reach (needed_gain(o, 1, 0, s)): so
/// singles and pairs compare by score, and a candidate passes iff J_ref − J_holdout ≥ needed.
double needed_gain(const DiagnosisOptions& options, std::size_t members, std::size_t parameters, double s);

struct CandidateOutcome {
  CandidateScore score;
  Config config;            // the effects added so far, refitted with it, plus it (last)
  Predictions predictions;  // fit and hold-out runs at the fitted values
  bool ok = false;
};

class CandidateFitter {
 public:
  CandidateFitter(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
                  const Simulator& simulate, const MisfitModel& misfit, const DiagnosisOptions& options)
      : runs_(runs), candidates_(candidates), sim_(simulate), misfit_(misfit), opt_(options) {}

  /// Predictions of the runs `which` with `config`, simulated on `jobs` threads. Throws
  /// std::runtime_error if the simulator returns a prediction of the wrong length.
  Predictions predict(const Config& config, const std::vector<std::size_t>& which, unsigned jobs) const;
  /// Fits `c` on top of `fold` (the effects added so far) and scores it against `current`.
  CandidateOutcome fit_candidate(const EffectCandidate& c, const Config& fold, const Predictions& current) const;
  /// A joint candidate (effect_selection.cpp "joint step"): the last `members` effects of
  /// `start` switched on together on top of the others (the effects added so far); every
  /// parameter of `start` is fitted from its value there. `at_start` holds the predictions of
  /// the fit runs at `start` (the screen's): the solver's first evaluation reuses them. Scored
  /// as fit_candidate, plus min_gain · s per member beyond the first.
  CandidateOutcome fit_joint(const Config& start, std::size_t members, const Predictions& at_start,
                             const Predictions& current) const;
  /// Refits the effects of `fold` alone on the fit set from their values (the fair reference of
  /// a round); `out` gets their fit and hold-out predictions. Returns the refitted config.
  Config refit_fold(const Config& fold, Predictions& out) const;
  /// Jointly refits `full` plus the effects `added` (appended) on all runs from their current
  /// values; `out` gets the predictions of all runs.
  Config refit_all(const Config& full, const Config& added, Predictions& out) const;
  const EffectCandidate& candidate(const std::string& name) const;
  /// The first of `values` (parameters of `c`) within bound_margin of its range from a bound,
  /// "" if all are interior.
  std::string parameter_at_bound(const EffectCandidate& c, const std::vector<double>& values) const;
  /// How far `after` moved from `before` (parameters of `c`) relative to stand_in_shift: > 1
  /// means a move beyond it (DiagnosisOptions::stand_in_shift); `which` gets the parameter.
  double relative_move(const EffectCandidate& c, const std::vector<double>& before, const std::vector<double>& after,
                       std::size_t& which) const;

 private:
  // The fitted parameters of a configuration as one vector, with their bounds, for the solver.
  struct FlatConfig {
    Config config;
    std::vector<std::pair<std::size_t, std::size_t>> slots;  // (effect, parameter) of config
    std::vector<double> values, lower, upper;
    std::vector<bool> linear;
    Config with(const std::vector<double>& v) const;
  };
  FlatConfig flatten(const Config& config) const;
  /// Least squares on `set` from the starts; nullopt when no start could be simulated.
  /// `evaluations` grows by the simulations of the set's runs made (CandidateScore).
  /// `at_best` gets the predictions of the set's runs at the returned values (simulated
  /// during the fit: they are not simulated again). `at_start`, if given, holds the
  /// predictions at flat.values (used instead of simulating that point).
  std::optional<Config> fit_config(const FlatConfig& flat, std::vector<std::vector<double>> starts,
                                   const SampleSet& set, unsigned jobs, int& evaluations, Predictions& at_best,
                                   const Predictions* at_start = nullptr) const;
  /// Fills the scores of `o` (o.config fitted, o.predictions of fit and hold-out runs) for the
  /// last `members` effects of o.config, against `current`.
  void score_outcome(CandidateOutcome& o, std::size_t members, const Predictions& current) const;
  /// `known` completed by simulating the runs of `which` it lacks, with `config`.
  Predictions complete(const Config& config, Predictions known, const std::vector<std::size_t>& which,
                       unsigned jobs) const;
  double signature_correlation(const Predictions& current, const Predictions& candidate) const;
  std::string rejection(const Config& members, const CandidateScore& score, double s) const;

  const std::vector<DiagnosisRun>& runs_;
  const std::vector<EffectCandidate>& candidates_;
  const Simulator& sim_;
  const MisfitModel& misfit_;
  const DiagnosisOptions& opt_;
};

}  // namespace shudder::analysis
