#include "analysis/effect_selection.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/residual_tracking.hpp"
#include "core/parallel_for.hpp"

namespace shudder::analysis {

namespace {

// The backward check after the greedy search. An effect added early can be a stand-in for one
// added later that explains more (a torque-cell gain takes the torque share of a load-cell gain
// in round 1; the load gain, which also moves the heat, comes later and makes it redundant).
// So each added effect is taken out in turn, the others refitted alone on the fit set, and the
// one whose removal costs the least held-out misfit is withdrawn if that cost is below what it
// would need to be accepted now ((min_gain + penalty·k)·s, the forward test's threshold).
// Repeated until every added effect pays for itself. Cost: one refit per added effect and pass,
// only when two or more effects were added.
void withdraw_redundant(Selection& sel, Config& fold, const CandidateFitter& fitter, const MisfitModel& misfit,
                        const DiagnosisOptions& opt) {
  while (fold.size() >= 2) {
    const double j_with = misfit.misfit(misfit.holdout(), sel.fold_predictions);
    const double s = std::max(1.0, j_with);
    std::size_t weakest = fold.size();
    double weakest_margin = 0.0;
    Config weakest_config;
    Predictions weakest_pred;
    for (std::size_t i = 0; i < fold.size(); ++i) {
      Config without = fold;
      without.erase(without.begin() + static_cast<std::ptrdiff_t>(i));
      Predictions pred = sel.fold_predictions;
      Config refit = fitter.refit_fold(without, pred);
      const double k = static_cast<double>(fold[i].values.size());
      const double cost = misfit.misfit(misfit.holdout(), pred) - j_with;
      const double margin = cost - (opt.min_gain + opt.penalty_per_parameter * k) * s;
      if (margin < 0.0 && (weakest == fold.size() || margin < weakest_margin)) {
        weakest = i;
        weakest_margin = margin;
        weakest_config = std::move(refit);
        weakest_pred = std::move(pred);
      }
    }
    if (weakest == fold.size()) return;
    const std::string name = fold[weakest].effect;
    fold = std::move(weakest_config);
    sel.fold_predictions = std::move(weakest_pred);
    // The full (all-runs) configuration without it, refitted jointly from its values.
    Config full;
    for (const auto& e : sel.full)
      if (e.effect != name) full.push_back(e);
    const Config base(full.begin(), full.end() - 1);
    sel.full = fitter.refit_all(base, full, sel.full_predictions);
    sel.steps.erase(std::remove_if(sel.steps.begin(), sel.steps.end(),
                                   [&](const DiagnosisStep& st) { return st.effect == name; }),
                    sel.steps.end());
    for (auto& st : sel.steps)
      for (const auto& e : sel.full)
        if (e.effect == st.effect)
          for (std::size_t j = 0; j < st.parameters.size() && j < e.values.size(); ++j)
            st.parameters[j].second = e.values[j];
    sel.withdrawn.push_back(name);
  }
}

}  // namespace

Selection select_effects(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
                         const CandidateFitter& fitter, const MisfitModel& misfit,
                         const DiagnosisOptions& opt, const Predictions& baseline) {
  Selection sel;
  Config fold;
  Config& full = sel.full;
  Predictions& fold_pred = sel.fold_predictions;
  Predictions& full_pred = sel.full_predictions;
  fold_pred = baseline;
  full_pred = baseline;
  StopReason& stop = sel.stop;
  for (int round = 0;; ++round) {
    bool within = true;
    std::vector<std::pair<std::string, double>> levels;
    for (const auto& c : misfit.channels()) {
      const double j = misfit.channel_misfit(c, misfit.all(), full_pred);
      within = within && j <= opt.noise_tolerance * opt.noise_tolerance;
      levels.emplace_back(c.name, std::sqrt(j));
    }
    if (within) {
      stop.kind = StopReason::Kind::kWithinNoise;
      stop.noise_tolerance = opt.noise_tolerance;
      stop.rms_over_noise = levels;
      break;
    }
    if (round >= opt.max_effects) {
      stop.kind = StopReason::Kind::kEffectLimit;
      stop.max_effects = opt.max_effects;
      break;
    }
    std::vector<const EffectCandidate*> open;
    for (const auto& c : candidates) {
      bool added = false;
      for (const auto& s : fold) added = added || s.effect == c.name;
      if (!added) open.push_back(&c);
    }
    if (open.empty()) {
      stop.kind = StopReason::Kind::kAllAdded;
      break;
    }
    // Longest fits first (most parameters: most evaluations), so that no long fit starts last
    // and leaves the other threads idle at the end of the round.
    std::stable_sort(open.begin(), open.end(), [](const EffectCandidate* a, const EffectCandidate* b) {
      return a->parameter_names.size() > b->parameter_names.size();
    });
    // The fair reference: the earlier effects refitted alone on the same fit set, so that what
    // re-fitting them gains is not credited to the newcomer.
    if (!fold.empty()) fold = fitter.refit_fold(fold, fold_pred);
    std::vector<CandidateOutcome> outcomes(open.size());
    parallel_for(open.size(), opt.jobs,
                 [&](std::size_t i) { outcomes[i] = fitter.fit_candidate(*open[i], fold, fold_pred); });
    std::stable_sort(outcomes.begin(), outcomes.end(), [](const CandidateOutcome& a, const CandidateOutcome& b) {
      if (a.ok != b.ok) return a.ok;
      return a.score.score < b.score.score;
    });
    std::vector<CandidateScore> scores;
    for (const auto& o : outcomes) scores.push_back(o.score);
    // The best-scored candidate that passes every acceptance test.
    const CandidateOutcome* chosen = nullptr;
    for (const auto& o : outcomes)
      if (!chosen && o.ok && o.score.rejection.empty()) chosen = &o;
    if (!chosen) {
      const CandidateOutcome& best = outcomes.front();
      const double k = static_cast<double>(best.score.parameters.size());
      const double s = std::max(1.0, misfit.misfit(misfit.holdout(), fold_pred));
      sel.last_round = scores;
      if (best.ok) {
        stop.kind = StopReason::Kind::kNoGain;
        stop.needed_gain = (opt.min_gain + opt.penalty_per_parameter * k) * s;
        stop.best_effect = best.score.effect;
        stop.best_gain = best.score.gain + opt.penalty_per_parameter * k * s;
        stop.best_rejection = best.score.rejection;
      } else {
        stop.kind = StopReason::Kind::kNoFit;
      }
      break;
    }
    const CandidateOutcome& best = *chosen;
    DiagnosisStep step;
    step.effect = best.score.effect;
    // The added candidate first (the step's reason speaks of it), the others best first.
    step.candidates.push_back(best.score);
    for (const auto& o : outcomes)
      if (&o != chosen) step.candidates.push_back(o.score);
    step.holdout_misfit_before = misfit.misfit(misfit.holdout(), fold_pred);
    step.holdout_misfit_after = best.score.holdout_misfit;
    step.holdout = misfit.rms(misfit.holdout(), best.predictions);
    const Predictions before = full_pred;
    fold = best.config;
    for (std::size_t kk = 0; kk < runs.size(); ++kk)
      if (best.predictions[kk]) fold_pred[kk] = best.predictions[kk];
    full = fitter.refit_all(full, fold, full_pred);
    const auto& c = fitter.candidate(step.effect);
    for (std::size_t j = 0; j < c.parameter_names.size(); ++j)
      step.parameters.emplace_back(c.parameter_names[j], full.back().values[j]);
    step.misfit = misfit.rms(misfit.all(), full_pred);
    step.description = c.description;
    step.torque_tracking_before = pooled_tracking(runs, before, true);
    step.temp_tracking_before = pooled_tracking(runs, before, false);
    sel.steps.push_back(std::move(step));
  }
  withdraw_redundant(sel, fold, fitter, misfit, opt);
  return sel;
}

}  // namespace shudder::analysis
