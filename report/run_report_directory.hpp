#pragma once
// The report directories of `shudder run --report DIR` and `shudder sweep --report DIR`
// (docs/plots.md "Report directories"): the summary, the verdict, the plots of report/plots and
// index.html (report/report_directory.hpp) linking them and the command's HDF5 file.

#include <string>

#include "dynamics/recording.hpp"
#include "io/hdf5_sweep.hpp"
#include "report/html_page.hpp"
#include "report/report_directory.hpp"

namespace shudder::report {

/// Report directory of a run: `dir`/summary.txt (`summary`), verdict.json (the recording's
/// verdict block, io/verdict_json.hpp; when it holds one), torque.png, temperature.png,
/// spectrum.png and, for rig runs (`rig`), spectrogram.png and stability_map.png (the latter
/// when the recording holds the map); a driveline run's coupling.png instead of torque.png and
/// spectrum.png. Last index.html: the verdict sentence, the summary, the verdict block as a
/// table, the figures and a link to `run_file` (the run's HDF5 file). Creates `dir`. A plot the
/// data cannot support (e.g. a record too short for a spectrum) is skipped and listed, not an
/// error.
Report write_run_report(const std::string& dir, const dynamics::Recording& rec, const std::string& name,
                        const std::string& summary, bool rig, const std::string& run_file);

/// Report directory of a sweep: `dir`/summary.txt, sweep.png and index.html (the summary, the
/// table of cases, the plot, a link to `sweep_file`).
Report write_sweep_report(const std::string& dir, const io::SweepTable& table, const std::string& name,
                          const std::string& summary, const std::string& sweep_file);

/// A run's verdict block as a table: quantity, value, units ("–" for an undefined number).
HtmlTable verdict_table(const dynamics::ResultBlock& verdict);

}  // namespace shudder::report
