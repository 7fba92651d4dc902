#pragma once
// Writes a run's verdict block (studies/run_verdict.hpp, /analysis/verdict in its HDF5) as
// JSON, format "shudder-verdict/1" (docs/formats/run_output.md): one flat object with the block's texts
// and scalars under the names the HDF5 uses, so the two never differ:
//   {"format": "shudder-verdict/1", "verdict": "vibration", "judged_signals": "...",
//    "operating_window": "...", "prediction": "...", "verdict_code": 1, "frequency_Hz": 377.9,
//    "amplitude_Nm": 41.2, ...}
// Hand-written (no JSON library in the dependencies): strings through io::json_string, numbers
// with 10 significant digits, NaN and ±infinity as null (a quantity that is undefined: no
// oscillation, not predicted, not recorded).

#include <string>

#include "dynamics/recording.hpp"

namespace shudder::io {

/// The block as JSON text (texts first, then scalars, each in the block's order).
std::string verdict_json(const dynamics::ResultBlock& verdict);

/// Writes verdict_json() to `path` through a temporary file and a rename (atomic_file.hpp).
/// Throws InputError naming `path` if it cannot be written.
void write_verdict_json(const dynamics::ResultBlock& verdict, const std::string& path);

}  // namespace shudder::io
