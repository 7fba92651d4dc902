#pragma once
// Shared by the diagnosis tests that build their runs from the shipped probe scenario
// (scenarios/diagnosis_probe.toml): its text at another load and start temperature with extra
// TOML appended, and a readable account of a diagnosis for assertion messages.
#include <string>

#include "analysis/diagnosis.hpp"
#include "report/diagnosis_narrative.hpp"
#include "tests/support/cli.hpp"

namespace shudder::test {

/// The probe scenario at `force_N` and `temp_C`, with `extra` (effect tables, …) appended.
inline std::string probe_scenario_text(const std::string& extra, double force_N, double temp_C) {
  std::string s = shipped_scenario_text("diagnosis_probe.toml");
  s = replace(s, "start_temp_C = 75.0", "start_temp_C = " + std::to_string(temp_C));
  s = replace(s, "normal_force_N = 12000.0", "normal_force_N = " + std::to_string(force_N));
  return s + "\n" + extra;
}

/// Verdict, conclusion, each step, the last round's candidates and the withdrawn effects.
inline std::string describe_diagnosis(const analysis::DiagnosisResult& r) {
  std::string s = report::verdict_sentence(r) + "\n" + report::diagnosis_conclusion(r) + "\n";
  for (const auto& st : r.steps) s += "  step " + report::step_reason(st) + "\n";
  for (const auto& c : r.last_round)
    s += "  last round " + report::effects_label(c.effect, c.joint_with) + " holdout J " +
         std::to_string(c.holdout_misfit) + " gain " + std::to_string(c.gain) + " r " +
         std::to_string(c.signature_correlation) + " " + c.rejection + "\n";
  for (const auto& f : r.withdrawn) s += "  withdrawn " + report::backward_finding_text(f) + "\n";
  return s;
}

}  // namespace shudder::test
