#pragma once
// A sweep's HDF5 file (FORMATS.md: "A sweep writes one file with a /cases table and one group
// per case"):
//   /cases/<column>      1-D (n_cases): one double dataset per swept key (named as the key) and
//                        per numeric result, `units` attribute; `simulated_verdict` as strings
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
  std::string fluid_text;                            // the base scenario's fluid file; "" = none
  std::vector<SweepColumn> columns;                  // swept keys first, then results
  std::string text_column_name = "simulated_verdict";
  std::vector<std::string> text_column;              // (n_cases)
  std::vector<std::string> case_scenarios;           // (n_cases)
  std::vector<dynamics::Recording> case_recordings;  // (n_cases) signals only are written
};

void write_sweep_hdf5(const std::string& path, const SweepOutput& sweep);

/// The /cases table of a sweep file (numeric columns in file order, the string column apart).
struct SweepTable {
  std::vector<SweepColumn> columns;
  std::string text_column_name;
  std::vector<std::string> text_column;
  const SweepColumn* find(const std::string& name) const {
    for (const auto& c : columns)
      if (c.name == name) return &c;
    return nullptr;
  }
};
SweepTable read_sweep_table(const std::string& path);

}  // namespace shudder::io
