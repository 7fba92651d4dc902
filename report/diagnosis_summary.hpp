#pragma once
// The diagnosis as `shudder diagnose` prints it: baseline, where model and runs disagree, each
// round's candidate table, what was added and why, the final model and the time it took.

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "io/scenario.hpp"

namespace shudder::report {

/// `skipped`: the effects that were no candidate, with why (rig_models::replay_candidates).
std::string diagnosis_summary(const io::Scenario& scenario, const analysis::DiagnosisResult& result,
                              const std::vector<std::string>& skipped);

}  // namespace shudder::report
