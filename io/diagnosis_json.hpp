#pragma once
// Writes a discrepancy-diagnosis result (analysis/diagnosis.hpp) as JSON, format
// "shudder-diagnosis/1" (docs/formats/diagnosis_json.md; every field, required and optional, in
// docs/formats/diagnosis_json.md). Hand-written like io/screening_json (no JSON library in the
// dependencies): strings escaped per RFC 8259 by io::json_string, numbers with 10 significant
// digits, NaN and ±infinity as null, so the text is always valid JSON.

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"

namespace shudder::io {

/// The result's sentences, as report/diagnosis_narrative.hpp words them: the file carries them
/// (docs/formats/diagnosis_json.md), the writer only places them.
struct DiagnosisSentences {
  std::string holdout;                    // what was held out
  std::vector<std::string> step_reasons;  // why each step's effect was added (one per step)
  std::string conclusion;
  std::string verdict;  // the verdict in one sentence, with the gap left
};

/// The result as JSON text (ends in a newline).
std::string diagnosis_json(const analysis::DiagnosisResult& r, const DiagnosisSentences& words);

/// Writes diagnosis_json() to `path` through a temporary file and a rename (atomic_file.hpp).
/// Throws InputError naming `path` if it cannot be written.
void write_diagnosis_json(const std::string& path, const analysis::DiagnosisResult& r, const DiagnosisSentences& words);

}  // namespace shudder::io
