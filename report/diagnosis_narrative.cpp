#include "report/diagnosis_narrative.hpp"

#include "report/text_format.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>
#include <vector>

namespace shudder::report {

namespace {

std::string fmt(double v, const char* f = "%.3g") { return number(v, f); }

}  // namespace

std::string holdout_text(const analysis::HoldoutSplit& split) {
  using Kind = analysis::HoldoutSplit::Kind;
  switch (split.kind) {
    case Kind::kNone: return {};
    case Kind::kLastRun: return "run '" + split.run + "' (fits use the other runs)";
    case Kind::kOddTenths: return "odd tenths of the run's time (fits use the even tenths)";
  }
  return {};
}

std::string stop_reason_text(const analysis::StopReason& stop) {
  using Kind = analysis::StopReason::Kind;
  switch (stop.kind) {
    case Kind::kWithinNoise: {
      std::string levels;
      for (const auto& [name, ratio] : stop.rms_over_noise)
        levels += (levels.empty() ? "" : ", ") + name + " " + fmt(ratio, "%.2f");
      return "every signal is within " + fmt(stop.noise_tolerance, "%.2g") + " x its noise (rms / noise: " + levels +
             ")";
    }
    case Kind::kEffectLimit: return "the limit of " + std::to_string(stop.max_effects) + " added effects was reached";
    case Kind::kAllAdded: return "every candidate effect has been added";
    case Kind::kNoGain:
      return "no candidate lowers the held-out misfit by more than " + fmt(stop.needed_gain) +
             " with interior parameters and a change that follows the residual (best: " + stop.best_effect +
             ", lowers it by " + fmt(stop.best_gain) + (stop.best_rejection.empty() ? "" : "; " + stop.best_rejection) +
             ")";
    case Kind::kNoFit: return "no candidate could be fitted";
    case Kind::kTie:
      return stop.best_effect + " and " + stop.tied_with +
             " explain the data equally (each lowers the held-out misfit by " + fmt(stop.best_gain) +
             "): the data cannot tell them apart, so neither is named";
  }
  return {};
}

std::string effects_label(const std::string& effect, const std::vector<std::string>& joint_with) {
  std::string s = effect;
  for (const auto& m : joint_with) s += " + " + m;
  return s;
}

std::string step_reason(const analysis::DiagnosisStep& step) {
  std::ostringstream os;
  os << effects_label(step.effect, step.joint_with);
  if (!step.joint_with.empty()) os << ", switched on together in one joint step,";
  if (!step.description.empty()) os << " (" << step.description << ")";
  os << ": ";
  const auto tr = [](const std::vector<std::pair<std::string, double>>& r) {
    return r.empty() ? std::string("nothing") : r.front().first + " (" + fmt(r.front().second, "%.2f") + ")";
  };
  os << "before it, the torque error tracked " << tr(step.torque_tracking_before) << " and the temperature error "
     << tr(step.temp_tracking_before) << ". The change "
     << (step.joint_with.empty() ? "this effect makes" : "they make together")
     << " matches that residual (signature r = "
     << fmt(step.candidates.empty() ? 0.0 : step.candidates.front().signature_correlation, "%.2f") << ")";
  if (!step.parameters.empty()) {
    os << " with ";
    for (std::size_t j = 0; j < step.parameters.size(); ++j)
      os << (j ? ", " : "") << step.parameters[j].first << " = " << fmt(step.parameters[j].second, "%.4g");
  }
  os << ", and " << (step.joint_with.empty() ? "it lowers" : "they lower") << " the held-out misfit from "
     << fmt(step.holdout_misfit_before) << " to " << fmt(step.holdout_misfit_after) << " (1 = noise level)";
  if (step.candidates.size() > 1) {
    const auto& next = step.candidates[1];
    os << "; the next best, " << effects_label(next.effect, next.joint_with) << ", reached "
       << fmt(next.holdout_misfit);
  }
  os << ".";
  return os.str();
}

std::string verdict_words(analysis::DiagnosisVerdict v) {
  switch (v) {
    case analysis::DiagnosisVerdict::kExplained: return "explained";
    case analysis::DiagnosisVerdict::kPartlyExplained: return "partly explained";
    case analysis::DiagnosisVerdict::kNotExplained: return "not explained";
  }
  return {};
}

std::string not_explained_text(const analysis::DiagnosisResult& r) {
  std::string reasons, cause;
  for (const auto& u : r.not_explained)
    if (!u.parameter.empty()) {
      reasons += (reasons.empty() ? "" : "; ") + u.reason;
      if (cause.empty()) cause = u.likely_cause;
    }
  if (reasons.empty() && !r.not_explained.empty()) {  // the gap: one reason for all
    reasons = r.not_explained.front().reason;
    cause = r.not_explained.front().likely_cause;
  }
  return reasons + (cause.empty() ? "" : " (likely cause: " + cause + ")");
}

std::string verdict_sentence(const analysis::DiagnosisResult& r) {
  std::ostringstream os;
  os << "Verdict: " << verdict_words(r.verdict);
  if (!r.missing_effects.empty()) {
    os << " by ";
    for (std::size_t i = 0; i < r.missing_effects.size(); ++i) os << (i ? ", " : "") << r.missing_effects[i];
  }
  std::string gaps;
  for (const auto& c : r.channels) {
    if (c.within) continue;
    gaps += (gaps.empty() ? "" : "; ") + c.signal + " RMS " + fmt(c.final_rms) + " against an error scale of " +
            fmt(c.error_scale) + " (" + fmt(std::sqrt(c.final_misfit), "%.2g") + "x)";
    std::string where;
    int shown = 0;
    for (const auto& d : r.final_disagreements)
      if (d.signal == c.signal && shown++ < 2)
        where += (where.empty() ? "" : ", ") + d.run + " " + fmt(d.t_start_s, "%.1f") + "-" + fmt(d.t_end_s, "%.1f") +
                 " s mean " + fmt(d.mean_error);
    if (!where.empty()) gaps += " at " + where;
  }
  if (!r.not_explained.empty()) {
    os << ": " << not_explained_text(r) << "; nothing is named";
    if (!gaps.empty()) os << "; with the baseline: " << gaps;
  } else if (gaps.empty()) {
    os << ": every channel within its error scale";
  } else {
    if (r.stop.kind == analysis::StopReason::Kind::kTie && r.missing_effects.empty())
      os << ": " << r.stop.best_effect << " and " << r.stop.tied_with
         << " close the gap equally, so neither is named; ";
    else
      os << (r.verdict == analysis::DiagnosisVerdict::kNotExplained ? ": no candidate closes the gap; "
                                                                    : "; a gap remains: ");
    os << gaps;
    if (!r.tolerance_given)
      os << " (no --tolerance given: a model-form gap could not be separated from a missing effect)";
  }
  os << ".";
  return os.str();
}

std::string diagnosis_conclusion(const analysis::DiagnosisResult& r) {
  const std::string stop = stop_reason_text(r.stop);
  std::ostringstream concl;
  if (!r.not_explained.empty()) {
    std::string tried;
    for (const auto& u : r.not_explained) tried += (tried.empty() ? "" : ", ") + u.effect;
    concl << "Not explained: " << not_explained_text(r) << ". The search added " << tried
          << ", which is therefore not named as missing; the final model is the baseline.";
  } else if (r.missing_effects.empty() && r.stop.kind == analysis::StopReason::Kind::kTie) {
    concl << "No effect is named: " << stop << ".";
  } else if (r.missing_effects.empty()) {
    concl << "Nothing is missing that the candidates could explain: " << stop << ".";
  } else {
    concl << "Missing: ";
    for (std::size_t i = 0; i < r.missing_effects.size(); ++i) concl << (i ? ", then " : "") << r.missing_effects[i];
    concl << ". Torque RMS " << fmt(r.baseline.torque_rms_Nm) << " -> " << fmt(r.final.torque_rms_Nm)
          << " Nm, temperature RMS " << fmt(r.baseline.temp_rms_C) << " -> " << fmt(r.final.temp_rms_C) << " C (noise "
          << fmt(r.noise_torque_Nm) << " Nm, " << fmt(r.noise_temp_C) << " C). The search stopped because " << stop
          << ".";
  }
  return concl.str();
}

std::string backward_finding_text(const analysis::BackwardFinding& f) {
  std::ostringstream os;
  os << effects_label(f.effect, f.joint_with) << ": without " << (f.joint_with.empty() ? "it" : "them")
     << " the held-out misfit rises by " << fmt(f.holdout_cost) << ", below the " << fmt(f.needed_gain)
     << " it would need";
  if (!f.stand_in.empty()) os << "; " << f.stand_in << " takes over (" << f.stand_in_move << ")";
  if (f.withdrawn)
    os << "; withdrawn";
  else
    os << "; kept: " << f.kept_because << " (the data cannot separate the two)";
  return os.str();
}

io::DiagnosisSentences diagnosis_sentences(const analysis::DiagnosisResult& r) {
  io::DiagnosisSentences words{holdout_text(r.holdout), {}, diagnosis_conclusion(r), verdict_sentence(r)};
  for (const auto& st : r.steps) words.step_reasons.push_back(step_reason(st));
  return words;
}

}  // namespace shudder::report
