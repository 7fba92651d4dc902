#pragma once
// A sweep's HDF5 file (docs/formats/sweep_output.md: "A sweep writes one file with a /cases table and one group
// per case"):
//   /cases/<column>      1-D (n_cases): one double dataset per swept key (named as the key) and
//                        per numeric result, `units` attribute; `simulated_verdict` and
//                        `simulated_message` as strings: a case whose run threw has verdict
//                        `failed`, NaN results and its error in `simulated_message` ("" for a
//                        case that ran)
//   /case_NNNNN/signals/<name>   the case's recorded signals (a chosen subset)
//   /case_NNNNN attribute `scenario`: the case's scenario text
//   root attributes `scenario` (the base scenario), `fluid` (its fluid file's text, if given),
//                   `shudder_version`, `created_utc`
// Signals are chunked and deflated as in a run file (hdf5_run.hpp).
// Written to a temporary name and renamed when complete. Implemented in hdf5_run.cpp, on the
// helpers and the library-wide HDF5 mutex of hdf5_util.hpp.

#include <string>
#include <utility>
#include <vector>

#include "dynamics/recording.hpp"

namespace shudder::io {

struct SweepColumn {
  std::string name;
  std::string units;
  std::vector<double> values;  // (n_cases)
};

struct SweepOutput {
  std::string base_scenario_text;
  std::string fluid_text;            // the base scenario's fluid file; "" = none
  std::vector<SweepColumn> columns;  // swept keys first, then results
  std::string text_column_name = "simulated_verdict";
  std::vector<std::string> text_column;              // (n_cases)
  std::vector<std::string> message_column;           // (n_cases) "" unless the case failed
  std::vector<std::string> case_scenarios;           // (n_cases)
  std::vector<dynamics::Recording> case_recordings;  // (n_cases) signals only are written
  /// Alternative to case_recordings: (n_cases) run files whose signals are copied into the case
  /// groups one case at a time ("" = a case without signals), so the writer's memory does not
  /// grow with the case count (a sweep's part files).
  std::vector<std::string> case_part_paths;
};

void write_sweep_hdf5(const std::string& path, const SweepOutput& sweep);

/// The name of /cases' message column and of a failed case's part-file attribute.
inline constexpr const char* kSweepMessageColumn = "simulated_message";

/// A sweep's part file for a case whose run threw: root attributes `scenario` (the case's text,
/// which marks it finished on resume) and `simulated_message` (the error), no signals. Read the
/// message back with read_run_attribute (io/hdf5_run.hpp); a part that ran has none ("").
void write_failed_case_part(const std::string& path, const std::string& scenario_text, const std::string& message);

/// The /cases table of a sweep file (numeric columns in file order, the string column apart).
struct SweepTable {
  std::vector<SweepColumn> columns;
  std::string text_column_name;
  std::vector<std::string> text_column;
  std::vector<std::string> message_column;  // empty for files written before the column existed
  const SweepColumn* find(const std::string& name) const {
    for (const auto& c : columns)
      if (c.name == name) return &c;
    return nullptr;
  }
};
SweepTable read_sweep_table(const std::string& path);

}  // namespace shudder::io
