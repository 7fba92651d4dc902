#pragma once
// The validation document of `shudder validate`: each target of scenarios/validation.toml
// (io/validation_targets.hpp) evaluated on its case's recording, the table printed, and
// <docs>/validation.md with its plots written. The document is date-free, so rerunning on the
// same build gives identical files.
//   value          signal interpolated linearly at time_s in the recording
//   mean           trapezoid rule on a 10 ms grid of interpolated values over [from_s, to_s]
//   rise, percent  as io::TargetKind says
// Pass/fail is decided on the unrounded values.

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "dynamics/recording.hpp"
#include "io/scenario.hpp"
#include "io/validation_targets.hpp"
#include "rig_models/model.hpp"

namespace shudder::report {

/// One validation case as run.
struct ValidationRun {
  std::string label;  // the case's label (validation.toml)
  io::Scenario sc;
  rig_models::PrescribedSlipModel model;  // Paper G's runs are prescribed slip
  dynamics::Recording rec;
};

/// A row of the targets table.
struct ValidationRow {
  std::string case_label, quantity, target, result, pass;  // pass: "yes", "NO" or "–" (info)
};

struct Figure {
  std::string file, heading;
};

/// One row per target, in the file's order; `runs` in the order of spec.cases.
std::vector<ValidationRow> evaluate_targets(const io::ValidationSpec& spec, const std::vector<ValidationRun>& runs);
/// The table as the terminal shows it (columns aligned by display width).
void print_validation_table(std::ostream& os, const std::vector<ValidationRow>& rows);
/// A plot per case, the comparison plot and the ramp plot, as PNGs in `docs` (needs gnuplot).
std::vector<Figure> write_validation_plots(const std::filesystem::path& docs, const io::ValidationSpec& spec,
                                           const std::vector<ValidationRun>& runs);
/// <docs>/validation.md, atomically.
void write_validation_doc(const std::filesystem::path& docs, const io::ValidationSpec& spec,
                          const std::vector<ValidationRun>& runs, const std::vector<ValidationRow>& rows,
                          const std::vector<Figure>& figs, bool plots);

}  // namespace shudder::report
