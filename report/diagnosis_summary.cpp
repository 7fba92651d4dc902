#include "report/diagnosis_summary.hpp"

#include <cstdio>
#include <sstream>

#include "report/diagnosis_narrative.hpp"
#include "report/text_format.hpp"

namespace shudder::report {

namespace {

std::string num(double v, const char* f = "%.3g") { return number(v, f); }

std::string parameters(const std::vector<std::pair<std::string, double>>& p) {
  std::string s;
  for (const auto& [k, v] : p) s += (s.empty() ? "" : ", ") + k + " = " + num(v, "%.4g");
  return s.empty() ? "-" : s;
}

void print_candidates(std::ostream& os, const std::vector<analysis::CandidateScore>& cs) {
  os << "    effect                          held-out J  gain     signature r  parameters\n";
  for (const auto& c : cs) {
    char line[256];
    const std::string name = effects_label(c.effect, c.joint_with);
    if (!c.failure.empty()) {
      std::snprintf(line, sizeof line, "    %-31s failed: %s\n", name.c_str(), c.failure.c_str());
    } else {
      std::snprintf(line, sizeof line, "    %-31s %-11.4g %-8.3g %-12.2f ", name.c_str(), c.holdout_misfit, c.gain,
                    c.signature_correlation);
    }
    os << line << (c.failure.empty() ? parameters(c.parameters) + "\n" : "");
  }
}

}  // namespace

DiagnosisSubject diagnosis_subject(const io::Scenario& scenario) {
  return {scenario.path, std::string(model_kind_name(scenario.kind())), scenario.enabled_effects};
}

std::string diagnosis_summary(const DiagnosisSubject& s, const analysis::DiagnosisResult& r,
                              const std::vector<std::string>& skipped) {
  std::ostringstream os;
  os << verdict_sentence(r) << "\n";
  os << "Diagnosis of " << r.runs.size() << " run(s) against " << s.path << " (" << s.kind << ")\n";
  os << "  baseline effects on: ";
  for (std::size_t i = 0; i < s.enabled_effects.size(); ++i) os << (i ? ", " : "") << s.enabled_effects[i];
  os << (s.enabled_effects.empty() ? "none" : "") << "\n";
  for (const auto& k : skipped) os << "  not a candidate: " << k << "\n";
  os << "  hold-out: " << holdout_text(r.holdout) << "\n";
  os << "Noise estimated from the data: torque " << num(r.noise_torque_Nm) << " Nm, temp " << num(r.noise_temp_C)
     << " C\n";
  os << "Baseline: torque RMS " << num(r.baseline.torque_rms_Nm) << " Nm, temp RMS " << num(r.baseline.temp_rms_C)
     << " C";
  for (const auto& c : r.channels)
    if (c.comparison != "pointwise") os << " (torque compared by " << c.comparison << ")";
  os << "\n";
  os << "Where they disagree (model - measured):\n";
  if (r.disagreements.empty()) os << "  nowhere above the noise\n";
  for (const auto& d : r.disagreements)
    os << "  " << d.run << "  " << d.signal << "  " << num(d.t_start_s, "%.2f") << "-" << num(d.t_end_s, "%.2f")
       << " s  mean " << num(d.mean_error) << "  tracks " << d.tracks << " (r = " << num(d.correlation, "%.2f")
       << ")\n";
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const auto& st = r.steps[i];
    os << "Round " << i + 1 << " candidates (fitted on the fit set, scored on the hold-out; J = 1 is noise):\n";
    print_candidates(os, st.candidates);
    os << "  -> added " << effects_label(st.effect, st.joint_with) << " (" << parameters(st.parameters)
       << "): torque RMS " << num(st.misfit.torque_rms_Nm) << " Nm, temp RMS " << num(st.misfit.temp_rms_C) << " C\n";
    os << "     why: " << step_reason(st) << "\n";
  }
  if (!r.last_round.empty()) {
    os << "Last round (nothing added):\n";
    print_candidates(os, r.last_round);
  }
  os << "Missing effects: ";
  for (std::size_t i = 0; i < r.missing_effects.size(); ++i) os << (i ? ", " : "") << r.missing_effects[i];
  os << (r.missing_effects.empty() ? "none" : "") << "\n";
  for (const auto& u : r.not_explained) {
    os << "Not named (added by the search, not found): " << u.effect;
    if (!u.parameters.empty()) os << " (" << parameters(u.parameters) << ")";
    os << ": " << u.reason << (u.likely_cause.empty() ? "" : "; likely cause: " + u.likely_cause) << "\n";
  }
  for (const auto& f : r.withdrawn) os << "Withdrawn by the backward check: " << backward_finding_text(f) << "\n";
  for (const auto& f : r.indistinguishable) os << "Not separable on these data: " << backward_finding_text(f) << "\n";
  if (!r.final_effects.empty()) {
    os << "Final model, refitted on all runs:";
    for (const auto& f : r.final_effects)
      os << "\n  " << f.effect << (f.parameters.empty() ? "" : "  " + parameters(f.parameters));
    os << "\n";
  }
  os << "Final: torque RMS " << num(r.final.torque_rms_Nm) << " Nm, temp RMS " << num(r.final.temp_rms_C) << " C";
  for (const auto& c : r.channels)
    if (c.signal != "torque_Nm" && c.signal != "temp_C")
      os << ", " << c.signal << " RMS " << num(c.baseline_rms) << " -> " << num(c.final_rms);
  os << "\nRemaining gap against the error scale (noise, replay reproduction, tolerance in quadrature):\n";
  for (const auto& c : r.channels)
    os << "  " << c.signal << "  RMS " << num(c.final_rms) << "  scale " << num(c.error_scale) << " (reproduction "
       << num(c.reproduction) << ", tolerance " << num(c.tolerance) << ")  " << (c.within ? "within" : "NOT within")
       << "\n";
  os << "" << diagnosis_conclusion(r) << "\n";
  os << "Time: " << num(r.wall_s) << " s wall; " << r.simulations << " simulations took " << num(r.simulation_thread_s)
     << " thread-s, the fitting around them " << num(r.fitting_thread_s) << " thread-s\n";
  return os.str();
}

}  // namespace shudder::report
