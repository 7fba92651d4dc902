#pragma once
// Named only when found: whether the effects the greedy search added (analysis/effect_selection)
// explain the data well enough to be reported as missing (docs/diagnosis.md "Named only when
// found"). They are not when, refitted on all runs,
//   * a parameter sits at (within DiagnosisOptions::bound_margin of its range from) a bound —
//     the data pull it there: the effect is stretched to absorb something of another shape
//     (a torque-cell gain at 0.5 for a friction law read at the wrong radius); or
//   * with them a channel's gap stays above found_gap_factor × its error scale (with a
//     tolerance), or above the verdict's noise_tolerance without one: a model-form gap cannot
//     then be told from a missing effect, so what the effects close may be that gap.
// Then none is named (they were fitted jointly: one stretched member makes the others'
// values suspect too) and each is reported with its reason and, where known, the likely cause.

#include <string>
#include <vector>

#include "analysis/candidate_fit.hpp"
#include "analysis/diagnosis.hpp"

namespace shudder::analysis {

/// The effects of `full` (refitted on all runs) not found, given the channels with them (every
/// one of `full`, each with its reason); empty when all are found or none was added.
std::vector<UnexplainedEffect> unexplained_effects(const Config& full, const CandidateFitter& fitter,
                                                   const std::vector<ChannelFit>& channels,
                                                   const DiagnosisOptions& options);

/// A likely cause when the data pull a parameter of `effect` to its bound ("" if none is known).
std::string likely_cause_at_bound(const std::string& effect);

}  // namespace shudder::analysis
