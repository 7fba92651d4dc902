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

/// Cartesian product: row i gives the value of every axis for case i (axis order kept).
std::vector<std::vector<double>> sweep_cases(const std::vector<SweepAxis>& axes);

}  // namespace shudder::io
