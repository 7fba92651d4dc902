#pragma once
// Report directory of a discrepancy diagnosis (analysis/diagnosis.hpp; contents listed in
// docs/formats/diagnosis_json.md):
//
//   summary.txt               the text the caller printed
//   candidates.md             per step the table of every candidate tried (fit and hold-out
//                             misfit, score, gain, signature correlation), then the last round,
//                             the one that stopped the search
//   <stem>_torque.png         per run in r.traces: measured, baseline and final torque vs time
//   <stem>_temp.png           the same for temp_C
//   <stem>_residuals.png      residual model − measured before (baseline, dashed) and after
//                             (final, solid): torque in the upper panel, temp_C in the lower,
//                             each with its zero line
//   index.html                the page tying them together (report/report_directory.hpp)
//
// Plots are drawn by report/gnuplot. Without gnuplot on PATH the PNGs are skipped and listed in
// Report::skipped (the text files are the report's substance; a machine without gnuplot still
// gets them). A run whose traces cannot be plotted (empty, columns of different lengths) or a
// plot gnuplot fails on is skipped the same way; an unwritable directory is an io::InputError.

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "report/plots.hpp"

namespace shudder::report {

/// File-name stem for a run name: the part after the last '/', without its extension, every
/// character outside [A-Za-z0-9_.-] replaced by '_', a leading '.' by '_' (no hidden files);
/// "run" if nothing is left.
std::string diagnosis_run_stem(const std::string& run);

/// The text of candidates.md.
std::string diagnosis_candidates_markdown(const analysis::DiagnosisResult& r);

/// Creates `dir` and writes the files above into it (each through a temporary name and a
/// rename), then index.html (the verdict sentence, the summary, the signals' table, the plots,
/// links to `data_files`: the command's other outputs, e.g. its JSON). Two runs with the same
/// stem get "_2", "_3", ... appended in the order of r.traces.
Report write_diagnosis_report(const std::string& dir, const analysis::DiagnosisResult& r,
                              const std::string& summary_text, const std::vector<std::string>& data_files = {});

}  // namespace shudder::report
