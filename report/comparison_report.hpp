#pragma once
// `shudder compare`: the printed table and the report directory (docs/characterisation.md):
//   summary.txt           the printed text
//   mu_v_<T>C.png         per screening temperature, every fluid's mu against speed (1–120 rpm)
// Without gnuplot the PNGs are skipped and listed; an unwritable directory is an io::InputError.
#include <string>
#include <utility>
#include <vector>

#include "clutch/fluid.hpp"
#include "report/plots.hpp"
#include "studies/fluid_comparison.hpp"

namespace shudder::report {

std::string comparison_summary(const studies::Comparison& c);

/// `dir`/summary.txt, one mu_v_<T>C.png per temperature and index.html linking `data_files`.
Report write_comparison_report(const std::string& dir, const studies::Comparison& c,
                               const std::vector<std::pair<std::string, clutch::Fluid>>& fluids,
                               const std::string& summary_text, const std::vector<std::string>& data_files = {});

}  // namespace shudder::report
