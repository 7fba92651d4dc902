#pragma once
// Writes a discrepancy-diagnosis result (analysis/diagnosis.hpp) as JSON, format
// "shudder-diagnosis/1" (FORMATS.md "Diagnosis result"; every field, required and optional, in
// docs/diagnosis_format.md). Hand-written like io/screening_json (no JSON library in the
// dependencies): strings escaped per RFC 8259 by io::json_string, numbers with 10 significant
// digits, NaN and ±infinity as null, so the text is always valid JSON.

#include <string>

#include "analysis/diagnosis.hpp"

namespace shudder::io {

/// The result as JSON text (ends in a newline).
std::string diagnosis_json(const analysis::DiagnosisResult& r);

/// Writes diagnosis_json() to `path` through a temporary file and a rename (atomic_file.hpp).
/// Throws InputError naming `path` if it cannot be written.
void write_diagnosis_json(const std::string& path, const analysis::DiagnosisResult& r);

}  // namespace shudder::io
