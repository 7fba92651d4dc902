#pragma once
// Writes a fluid screening report (studies/fluid_screening.hpp) as JSON, format
// "shudder-screen/1" (docs/screening.md). Hand-written (no JSON library in the dependencies):
// strings escaped per RFC 8259, numbers with 10 significant digits, NaN and ±infinity as null.
// Every per-index array is aligned with "temperatures_C".

#include <string>

#include "studies/fluid_screening.hpp"

namespace shudder::io {

/// `s` as a JSON string literal, quotes included (", \, control characters escaped; UTF-8
/// passed through).
std::string json_string(const std::string& s);

/// The report as JSON text. `fluid_file` is recorded as given.
std::string screening_json(const studies::ScreeningReport& report, const std::string& fluid_file);

/// Writes screening_json() to `path` through a temporary file and a rename (atomic_file.hpp).
/// Throws InputError naming `path` if it cannot be written.
void write_screening_json(const studies::ScreeningReport& report, const std::string& fluid_file,
                          const std::string& path);

}  // namespace shudder::io
