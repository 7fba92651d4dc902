#pragma once
// The greedy search of the diagnosis (analysis/diagnosis.hpp, "selection"): each round fits
// every candidate not yet added (analysis/candidate_fit.hpp) on top of the effects added so
// far, adds the best if it lowers the hold-out misfit by more than min_gain + penalty·k, and
// refits all added effects jointly on all runs. It stops when every channel is within
// noise_tolerance·σ, at max_effects, when every candidate is added, or when none gains enough.
// Then a backward check withdraws any added effect the others make redundant, with a tie rule
// for effects the data cannot separate (effect_selection.cpp).

#include <string>
#include <vector>

#include "analysis/candidate_fit.hpp"
#include "analysis/diagnosis.hpp"
#include "analysis/misfit.hpp"

namespace shudder::analysis {

struct Selection {
  std::vector<DiagnosisStep> steps;
  std::vector<CandidateScore> last_round;  // the round that stopped the search (if by gain)
  StopReason stop;
  Config full;                   // added effects, last joint refit on all runs
  Predictions fold_predictions;  // fit/hold-out predictions of the last accepted fold
  Predictions full_predictions;  // all runs with `full`
  // Added in the greedy search, then taken out by the backward check (a stand-in for an
  // effect added later); their steps are removed from `steps`. And those the check could have
  // taken out but kept by its tie rule (DiagnosisResult::withdrawn, indistinguishable).
  std::vector<BackwardFinding> withdrawn, indistinguishable;
};

Selection select_effects(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
                         const CandidateFitter& fitter, const MisfitModel& misfit, const DiagnosisOptions& options,
                         const Predictions& baseline);

}  // namespace shudder::analysis
