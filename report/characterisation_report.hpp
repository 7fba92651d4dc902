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

#include "analysis/breakaway.hpp"
#include "analysis/friction_characterisation.hpp"
#include "report/plots.hpp"
#include "studies/inverse_characterisation.hpp"

namespace shudder::report {

/// The summary printed by the command: ramps, rows and their residuals, up/down agreement.
std::string characterisation_summary(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                                     const std::string& fluid_path);

/// `--method inverse`: both methods side by side — per row the RMS/max residual of each law
/// against its own compensated data and mu at the first, middle and last node — the replayed
/// torque's RMS misfit with each law, the thermal calibration and the iterations.
std::string method_comparison_summary(const studies::InverseCharacterisation& r,
                                      const analysis::CharacterisationSettings& sensor_settings);

/// "1.28–1.31 over 3 starts" style range of the measured events (for the fluid file's source).
std::string breakaway_range(const analysis::BreakawayMeasurement& m);

/// The breakaway lines of the printout: the ratio written, its source, and each start from rest
/// (run, time, peak mu, kinetic mu at the peak's speed, ratio).
std::string breakaway_summary(const analysis::BreakawayMeasurement& m, double written_ratio, const std::string& source);

/// Also writes index.html (report/report_directory.hpp) linking `data_files` (the fitted fluid
/// file, the JSON).
Report write_characterisation_report(const std::string& dir, const analysis::Characterisation& c,
                                     const std::string& summary_text, const std::vector<std::string>& data_files = {});

}  // namespace shudder::report
