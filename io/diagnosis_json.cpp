// JSON writer for the diagnosis result; see diagnosis_json.hpp and docs/formats/diagnosis_json.md.
#include "io/diagnosis_json.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/screening_json.hpp"
#include "io/json_number.hpp"

namespace shudder::io {

namespace {

using analysis::CandidateScore;
using analysis::DiagnosisStep;
using analysis::Disagreement;
using analysis::Misfit;
using analysis::Tracking;
using Pairs = std::vector<std::pair<std::string, double>>;

// One JSON object, members appended in order. Built on a stream rather than chained string
// `+`: GCC 12 flags `"..." + std::string&&` with a false-positive -Wrestrict at -O3.
class Object {
 public:
  explicit Object(std::string separator = ", ") : sep_(std::move(separator)) {}
  Object& raw(const char* k, const std::string& json) {
    os_ << (first_ ? "" : sep_) << '"' << k << "\": " << json;
    first_ = false;
    return *this;
  }
  Object& num(const char* k, double v) { return raw(k, json_number(v)); }
  Object& str(const char* k, const std::string& v) { return raw(k, json_string(v)); }
  std::string text() const {
    std::string t = "{";
    t += os_.str();
    t += '}';
    return t;
  }

 private:
  std::string sep_;
  std::ostringstream os_;
  bool first_ = true;
};

std::string strings(const std::vector<std::string>& v) {
  std::ostringstream os;
  os << '[';
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? ", " : "") << json_string(v[i]);
  os << ']';
  return os.str();
}

std::string object_of(const Pairs& p) {
  std::ostringstream os;
  os << '{';
  for (std::size_t i = 0; i < p.size(); ++i)
    os << (i ? ", " : "") << json_string(p[i].first) << ": " << json_number(p[i].second);
  os << '}';
  return os.str();
}

// "[]" or one element per line at `indent`, the closing bracket one level (2 spaces) out.
template <class T, class F>
std::string list(const std::vector<T>& v, const std::string& indent, F element) {
  if (v.empty()) return "[]";
  std::ostringstream os;
  os << "[\n";
  for (std::size_t i = 0; i < v.size(); ++i) os << indent << element(v[i]) << (i + 1 < v.size() ? ",\n" : "\n");
  os << indent.substr(0, indent.size() - 2) << ']';
  return os.str();
}

std::string misfit(const Misfit& m, double holdout_misfit) {
  return Object()
      .num("torque_rms_Nm", m.torque_rms_Nm)
      .num("temp_rms_C", m.temp_rms_C)
      .num("holdout_misfit", holdout_misfit)
      .text();
}

std::string disagreement(const Disagreement& d) {
  return Object()
      .str("run", d.run)
      .str("signal", d.signal)
      .num("t_start_s", d.t_start_s)
      .num("t_end_s", d.t_end_s)
      .num("mean_error", d.mean_error)
      .str("tracks", d.tracks)
      .num("correlation", d.correlation)
      .text();
}

std::string channel(const analysis::ChannelFit& c) {
  return Object()
      .str("signal", c.signal)
      .str("comparison", c.comparison)
      .num("noise", c.noise)
      .num("baseline_rms", c.baseline_rms)
      .num("final_rms", c.final_rms)
      .num("baseline_misfit", c.baseline_misfit)
      .num("final_misfit", c.final_misfit)
      .num("error_scale", c.error_scale)
      .num("reproduction", c.reproduction)
      .num("tolerance", c.tolerance)
      .text();
}

std::string tracking(const Tracking& t) {
  return Object().str("run", t.run).str("signal", t.signal).raw("correlations", object_of(t.correlations)).text();
}

std::string candidate(const CandidateScore& c) {
  Object o;
  o.str("effect", c.effect);
  if (!c.joint_with.empty()) o.raw("joint_with", strings(c.joint_with));
  o.raw("parameters", object_of(c.parameters))
      .num("fit_misfit", c.fit_misfit)
      .num("holdout_misfit", c.holdout_misfit)
      .num("score", c.score)
      .num("gain", c.gain)
      .num("signature_correlation", c.signature_correlation)
      .raw("evaluations", std::to_string(c.evaluations));
  // Present only for a failed candidate, so "has failure" is the test a reader needs.
  if (!c.failure.empty()) o.str("failure", c.failure);
  if (c.failure.empty() && !c.rejection.empty()) o.str("rejected", c.rejection);
  return o.text();
}

// Steps are large: one member per line, the candidates one per line below.
std::string step(const DiagnosisStep& st, const std::string& reason) {
  Object o(",\n      ");
  o.str("effect", st.effect);
  if (!st.joint_with.empty()) o.raw("joint_with", strings(st.joint_with));
  o.raw("parameters", object_of(st.parameters))
      .num("torque_rms_Nm", st.misfit.torque_rms_Nm)
      .num("temp_rms_C", st.misfit.temp_rms_C)
      .num("holdout_torque_rms_Nm", st.holdout.torque_rms_Nm)
      .num("holdout_temp_rms_C", st.holdout.temp_rms_C)
      .num("holdout_misfit_before", st.holdout_misfit_before)
      .num("holdout_misfit_after", st.holdout_misfit_after)
      .str("reason", reason)
      .raw("candidates", list(st.candidates, "        ", candidate));
  const std::string t = o.text();
  std::ostringstream os;
  os << "{\n      " << t.substr(1, t.size() - 2) << "\n    }";
  return os.str();
}

std::string verdict_key(analysis::DiagnosisVerdict v) {
  switch (v) {
    case analysis::DiagnosisVerdict::kExplained: return "explained";
    case analysis::DiagnosisVerdict::kPartlyExplained: return "partly_explained";
    case analysis::DiagnosisVerdict::kNotExplained: return "not_explained";
  }
  return {};
}

// The gap left per channel, with the final model's disagreement segments of that channel.
std::string remaining(const analysis::DiagnosisResult& r) {
  return list(r.channels, "    ", [&](const analysis::ChannelFit& c) {
    std::vector<Disagreement> open;
    for (const auto& d : r.final_disagreements)
      if (d.signal == c.signal) open.push_back(d);
    return Object()
        .str("signal", c.signal)
        .num("rms", c.final_rms)
        .num("error_scale", c.error_scale)
        .num("rms_over_scale", std::sqrt(c.final_misfit))
        .raw("within", c.within ? "true" : "false")
        .raw("segments", list(open, "      ", disagreement))
        .text();
  });
}

std::string backward_finding(const analysis::BackwardFinding& f) {
  Object o;
  o.str("effect", f.effect);
  if (!f.joint_with.empty()) o.raw("joint_with", strings(f.joint_with));
  o.raw("parameters", object_of(f.parameters))
      .num("holdout_cost", f.holdout_cost)
      .num("needed_gain", f.needed_gain)
      .str("stand_in", f.stand_in)
      .str("stand_in_move", f.stand_in_move);
  if (!f.withdrawn) o.str("kept_because", f.kept_because);
  return o.text();
}

std::string unexplained(const analysis::UnexplainedEffect& u) {
  Object o;
  o.str("effect", u.effect).raw("parameters", object_of(u.parameters)).str("parameter_at_bound", u.parameter);
  if (!u.parameter.empty()) o.num("bound", u.bound);
  return o.str("reason", u.reason).str("likely_cause", u.likely_cause).text();
}

std::string fitted_effect(const analysis::FittedEffect& f) {
  return Object().str("effect", f.effect).raw("parameters", object_of(f.parameters)).text();
}

}  // namespace

std::string diagnosis_json(const analysis::DiagnosisResult& r, const DiagnosisSentences& words) {
  if (words.step_reasons.size() != r.steps.size())
    throw std::logic_error("diagnosis_json: one reason per step is needed");
  std::vector<std::string> steps;
  for (std::size_t i = 0; i < r.steps.size(); ++i) steps.push_back(step(r.steps[i], words.step_reasons[i]));
  Object o(",\n  ");
  o.str("format", "shudder-diagnosis/1")
      .str("shudder_version", SHUDDER_VERSION)
      .str("verdict", verdict_key(r.verdict))
      .str("verdict_text", words.verdict)
      .raw("runs", strings(r.runs))
      .raw("noise", Object().num("torque_Nm", r.noise_torque_Nm).num("temp_C", r.noise_temp_C).text())
      .str("holdout", words.holdout)
      .raw("baseline", misfit(r.baseline, r.baseline_holdout_misfit))
      .raw("disagreements", list(r.disagreements, "    ", disagreement))
      .raw("tracking", list(r.tracking, "    ", tracking))
      .raw("steps", list(steps, "    ", [](const std::string& text) { return text; }))
      .raw("missing_effects", strings(r.missing_effects))
      .raw("not_explained", list(r.not_explained, "    ", unexplained))
      .raw("tolerance_given", r.tolerance_given ? "true" : "false")
      .raw("withdrawn_effects", list(r.withdrawn, "    ", backward_finding))
      .raw("indistinguishable_effects", list(r.indistinguishable, "    ", backward_finding))
      .raw("last_round", list(r.last_round, "    ", candidate))
      .raw("final", misfit(r.final, r.final_holdout_misfit))
      .raw("final_effects", list(r.final_effects, "    ", fitted_effect))
      .raw("channels", list(r.channels, "    ", channel))
      .raw("final_disagreements", list(r.final_disagreements, "    ", disagreement))
      .raw("remaining", remaining(r))
      .str("conclusion", words.conclusion)
      .raw("timing", Object()
                         .num("simulation_thread_s", r.simulation_thread_s)
                         .num("fitting_thread_s", r.fitting_thread_s)
                         .num("wall_s", r.wall_s)
                         .raw("simulations", std::to_string(r.simulations))
                         .text());
  const std::string t = o.text();
  std::ostringstream os;
  os << "{\n  " << t.substr(1, t.size() - 2) << "\n}\n";
  return os.str();
}

void write_diagnosis_json(const std::string& path, const analysis::DiagnosisResult& r,
                          const DiagnosisSentences& words) {
  write_text_file_atomically(path, diagnosis_json(r, words));
}

}  // namespace shudder::io
