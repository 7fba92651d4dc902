#pragma once
// A logger's CSV turned into a measured run (io/measured_run.hpp): columns mapped and converted
// (io/import_mapping.hpp), units checked for plausibility (io/import_plausibility.hpp), rows
// checked as the measured run's reader checks them, and the metadata a user did not give filled
// with documented defaults (a warning each). `shudder import` writes the result;
// docs/formats/import_mapping.md is the user's reference.

#include <string>
#include <utility>
#include <vector>

#include "io/import_mapping.hpp"
#include "io/measured_run.hpp"

namespace shudder::io {

/// The metadata an import writes when it is not given: rig, temp_sensor, oil_flow_ml_min (the
/// thesis rig's values, those of `shudder run --measurement`).
const std::vector<std::pair<std::string, std::string>>& import_metadata_defaults();

struct ImportResult {
  MeasuredRun run;                    // path = the logger file
  std::vector<std::string> mapping;   // "time_ms -> time_s (ms)", one per written column
  std::vector<std::string> ignored;   // logger columns not written
  std::vector<std::string> warnings;  // one line each, without "warning: "
  char delimiter = ',';
  char decimal = '.';
};

/// `path` as a measured run when `spec` maps nothing and names no mapping file (`maps` empty,
/// `from_mapping_file` false), else imported as a logger's CSV with it; the import's warnings
/// are appended to `warnings`. For the commands that read measured runs (`characterise`,
/// `diagnose` with --map/--mapping).
MeasuredRun read_measured_or_logger(const std::string& path, const ImportSpec& spec,
                                    std::vector<std::string>& warnings);

/// Reads and converts `logger_path`; InputError (file, line or column, what is allowed) on
/// anything that cannot become a valid measured run.
ImportResult import_logger(const std::string& logger_path, const ImportSpec& spec);

}  // namespace shudder::io
