#pragma once
// Sweep specifications: `--set KEY=START:STOP:STEP` (inclusive of STOP within 1e-9 of a step) or
// `--set KEY=V1,V2,...`; several --set give the cartesian product, the last key varying fastest.

#include <string>
#include <vector>

namespace shudder::io {

struct SweepAxis {
  std::string key;             // dotted scenario key, e.g. rig.torsion_bar.natural_frequency_Hz
  std::vector<double> values;  // in sweep order
};

/// Parses one --set argument; throws InputError (key "--set") naming the argument and the form.
SweepAxis parse_sweep_axis(const std::string& arg);

/// Rejects a key given twice (the cases would repeat, or a run's second value would silently
/// win) with an InputError naming it.
void require_distinct_keys(const std::vector<SweepAxis>& axes);

/// One `run --set KEY=VALUE`: the sweep's parser, so the same keys, numbers and messages, with
/// exactly one value (a range or list is an InputError pointing to `shudder sweep`).
SweepAxis parse_set_value(const std::string& arg);

/// Cartesian product: row i gives the value of every axis for case i (axis order kept).
std::vector<std::vector<double>> sweep_cases(const std::vector<SweepAxis>& axes);

}  // namespace shudder::io
