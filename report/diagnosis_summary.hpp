#pragma once
// The diagnosis as `shudder diagnose` prints it: baseline, where model and runs disagree, each
// round's candidate table, what was added and why, the final model and the time it took.

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "io/scenario.hpp"

namespace shudder::report {

/// What was diagnosed, as the summary names it.
struct DiagnosisSubject {
  std::string path;                          // the scenario file
  std::string kind;                          // e.g. "rig", "network clutch 'launch_clutch'"
  std::vector<std::string> enabled_effects;  // the baseline's
};
DiagnosisSubject diagnosis_subject(const io::Scenario& scenario);

/// `skipped`: the effects that were no candidate, with why (studies::replay_candidates).
std::string diagnosis_summary(const DiagnosisSubject& subject, const analysis::DiagnosisResult& result,
                              const std::vector<std::string>& skipped);

}  // namespace shudder::report
