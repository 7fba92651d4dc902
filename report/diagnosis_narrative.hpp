#pragma once
// The diagnosis in plain words (the sentences of docs/formats/diagnosis_json.md: a step's
// "reason", the "conclusion"), written from the numbers analysis/diagnosis.hpp returns. Used by
// the JSON writer, the Markdown report and the terminal summary, so all say the same.

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "io/diagnosis_json.hpp"

namespace shudder::report {

/// What was held out, e.g. "run 'b.csv' (fits use the other runs)"; empty for kNone.
std::string holdout_text(const analysis::HoldoutSplit& split);
/// Why the search stopped, e.g. "every signal is within 1.1 x its noise (rms / noise: ...)".
std::string stop_reason_text(const analysis::StopReason& stop);
/// Why a step's effect was added: what the residual tracked before it, its signature, its
/// parameters and the hold-out misfit it reached, against the next best candidate.
std::string step_reason(const analysis::DiagnosisStep& step);
/// "explained", "partly explained", "not explained".
std::string verdict_words(analysis::DiagnosisVerdict v);
/// Why the effects the search added are not named (DiagnosisResult::not_explained): the
/// parameters the data pull to their bounds, or the gap left, and the likely cause; "" if none.
std::string not_explained_text(const analysis::DiagnosisResult& result);
/// The summary's first line: the verdict, what was named, and where and how big the gap left
/// is per channel against its error scale.
std::string verdict_sentence(const analysis::DiagnosisResult& result);
/// One paragraph: what is missing, the RMS before and after against the noise, why it stopped.
std::string diagnosis_conclusion(const analysis::DiagnosisResult& result);
/// One backward-check finding in words: withdrawn (the others stand in for it) or kept by the
/// tie rule (the data cannot separate it from its stand-in), with the held-out cost.
std::string backward_finding_text(const analysis::BackwardFinding& f);
/// An added effect or joint candidate by name: "a", or "a + b" for effects switched on
/// together in one joint step (analysis/joint_step.hpp).
std::string effects_label(const std::string& effect, const std::vector<std::string>& joint_with);
/// All of the above for the JSON file.
io::DiagnosisSentences diagnosis_sentences(const analysis::DiagnosisResult& result);

}  // namespace shudder::report
