#pragma once
// The joint step of the greedy search (analysis/effect_selection.hpp). Parameter-free switches
// (an effect without fitted parameters, e.g. temperature- and load-dependent friction) can be
// right only together: on three Case 2 runs with every effect off, each alone is beaten by a
// 1.1 % load-cell gain on the 14.8 kN hold-out run, while both together reach the true model's
// held-out J (1.02 against 1.16). A one-at-a-time search never takes both, so each round also
// offers pairs as one candidate:
//
//   * every pair of open switches, on top of the effects added so far;
//   * each open switch with the round's best-scored single candidate (at its fitted values),
//     when that candidate has parameters (a switch is already paired with the other switches).
//
// Cost: each pair is first screened by one simulation of every fit run at its start (the added
// effects' values, both members on; the hold-out runs would not change the ranking); only the
// pair with the lowest fit-set misfit there is fitted (all parameters of the added effects and
// of the members jointly, as a single candidate is), and the fit reuses the screen's
// simulations at its start. So a round costs (pairs × fit runs) simulations and one fit more:
// its evaluations × fit runs (CandidateScore::evaluations), then the hold-out runs once at the
// fitted values.
//
// Acceptance (analysis/candidate_fit.hpp): the pair is scored like a single candidate, plus
// min_gain · s for its second member: score = J_holdout + penalty · k · s + min_gain · s, gain
// = J_ref − score ≥ min_gain · s. So a pair of switches (k = 0) must lower the held-out misfit
// by 2 · min_gain · s: it counts as two effects, each paying the gain an effect of its own must
// show, and no parameter price (it fits nothing). Its members' parameters must be interior and
// the change it makes must follow the residual, as for a single. And a member must not do as
// well alone: a pair whose score is not below that of each member fitted alone this round is
// rejected ("no better than X alone"), so a switch cannot ride in beside an effect that
// explains the gap by itself.

#include <optional>
#include <vector>

#include "analysis/candidate_fit.hpp"

namespace shudder::analysis {

/// The round's joint candidate: the pairs above screened, the best one fitted and scored
/// against `fold_pred`; nullopt when the round has no pair (fewer than two open switches and
/// no best single with parameters). `singles` are the round's fitted single candidates.
std::optional<CandidateOutcome> joint_candidate(const std::vector<const EffectCandidate*>& open,
                                                const std::vector<CandidateOutcome>& singles, const Config& fold,
                                                const Predictions& fold_pred, const CandidateFitter& fitter,
                                                const MisfitModel& misfit, const DiagnosisOptions& options);

}  // namespace shudder::analysis
