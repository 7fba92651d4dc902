#pragma once
// Report directory of `shudder characterise` (docs/characterisation.md):
//
//   summary.txt               the text the command printed
//   mu_v_<load>kN.png         per load: the rows' compensated, speed-binned measured mu
//                             (points) and the fitted law at the row (line), against speed
//   residuals.png             law − measured (binned means) per row against speed
//   up_down_<load>kN.png      per load: mean up- and down-ramp mu at the node speeds before
//                             (dashed) and after (solid) temperature compensation
//
// Without gnuplot on PATH the PNGs are skipped and listed in Report::skipped; an unwritable
// directory is an io::InputError.

#include <string>

#include "analysis/friction_characterisation.hpp"
#include "report/plots.hpp"

namespace shudder::report {

/// The summary printed by the command: ramps, rows and their residuals, up/down agreement.
std::string characterisation_summary(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                                     const std::string& fluid_path);

Report write_characterisation_report(const std::string& dir, const analysis::Characterisation& c,
                                     const std::string& summary_text);

}  // namespace shudder::report
