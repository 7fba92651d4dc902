#pragma once
// The plots of `shudder plot` and of the report directories of `shudder run` / `sweep`
// (docs/plots.md), built from what a run or sweep file holds and drawn by report/gnuplot:
//
//   torque         torque_Nm (and clutch_torque_Nm) vs time, sliding speed on the right axis
//   temperature    temp_C, ir_temp_C, sump_temp_C, interface_max_temp_C vs time
//   spectrum       Hann-windowed amplitude spectrum of the torque over the whole record (mean
//                  removed), log amplitude, the detected shudder peak (analysis/
//                  shudder_detection) marked and labelled
//   spectrogram    short-time torque PSD in dB over time x frequency, in the band 0.5–2.5 times
//                  the dominant frequency, with that frequency and the onset marked
//   stability_map  margin (1/s) of the stored /analysis/stability_map over slip speed x
//                  interface temperature, its zero contour (stable | unstable boundary) and the
//                  run's own path through the map
//   sweep          a sweep's /cases vs its first swept key: predicted and simulated frequency,
//                  predicted margin (right axis), the simulated verdict as markers on it
//
// A builder throws io::InputError naming `source` (the file) when the data lack what the plot
// needs, e.g. "run.h5: no /analysis/stability_map: it is written for rig scenarios".

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dynamics/recording.hpp"
#include "report/gnuplot.hpp"
#include "io/hdf5_sweep.hpp"

namespace shudder::report {

enum class PlotKind { kTorque, kTemperature, kSpectrum, kSpectrogram, kStabilityMap, kSweep, kCoupling };

/// The names accepted by --what, in PlotKind order.
const std::vector<std::string>& plot_kind_names();
std::optional<PlotKind> parse_plot_kind(std::string_view name);

/// The `[scenario] name` of a scenario text; `fallback` if the text has none or does not parse.
std::string scenario_name(const std::string& scenario_text, const std::string& fallback);

/// Builders: `name` titles the plot (the scenario's name), `source` names the data in errors.
Plot torque_plot(const dynamics::Recording& rec, const std::string& name, const std::string& source);
Plot temperature_plot(const dynamics::Recording& rec, const std::string& name,
                      const std::string& source);
Plot spectrum_plot(const dynamics::Recording& rec, const std::string& name,
                   const std::string& source);
Plot spectrogram_plot(const dynamics::Recording& rec, const std::string& name,
                      const std::string& source);
Plot stability_map_plot(const dynamics::Recording& rec, const std::string& name,
                        const std::string& source);
Plot sweep_plot(const io::SweepTable& table, const std::string& name, const std::string& source);

/// The plot of `kind` for a run recording (every kind but kSweep).
Plot run_plot(PlotKind kind, const dynamics::Recording& rec, const std::string& name,
              const std::string& source);

/// Contour line(s) of `values` (n_x x n_y on the grid x, y) at `level` by marching squares:
/// one straight segment per grid cell the level crosses (linear interpolation along the cell
/// edges; saddles resolved by the cell's mean), segments separated by NaN points so the line
/// breaks between them. Cells with a non-finite corner are skipped. Empty if nothing crosses.
Series contour_series(const std::vector<double>& x, const std::vector<double>& y,
                      const Eigen::MatrixXd& values, double level, const std::string& label);

/// Reads the run or sweep file `h5_path` and writes the plot of `kind` to `out_path` (.png or
/// .svg). io::InputError when the file is unreadable or lacks what the plot needs.
void plot_file(const std::string& h5_path, PlotKind kind, const std::string& out_path);

/// Creates the report directory `dir` (and its parents); io::InputError naming it when it cannot.
void make_report_dir(const std::string& dir);

struct Report;
/// Writes `plot` to `dir`/`file` and lists it in `report.files`; a plot gnuplot fails to draw is
/// listed in `report.skipped` with gnuplot's reason instead. An unwritable destination stays an
/// io::InputError (the caller's problem, as for the report's text files).
void add_report_plot(Report& report, const std::string& dir, const std::string& file, const Plot& plot);

/// The `report.skipped` reason for plots when gnuplot is not on PATH.
inline constexpr const char* kGnuplotMissing = "gnuplot not found; install gnuplot (Debian: gnuplot-nox)";

struct Report {
  std::vector<std::string> files;    // written, in order
  std::vector<std::string> skipped;  // "spectrum.png: <why>" for plots the data do not support
};

/// Report directory of a run: `dir`/summary.txt (`summary`), verdict.json (the recording's
/// verdict block, io/verdict_json.hpp; when it holds one), torque.png, temperature.png,
/// spectrum.png and, for rig runs (`rig`), spectrogram.png and stability_map.png (the latter
/// when the recording holds the map). Creates `dir`. A plot the data cannot support (e.g. a
/// record too short for a spectrum) is skipped and listed, not an error.
Report write_run_report(const std::string& dir, const dynamics::Recording& rec,
                        const std::string& name, const std::string& summary, bool rig);

/// Report directory of a sweep: `dir`/summary.txt and sweep.png.
Report write_sweep_report(const std::string& dir, const io::SweepTable& table, const std::string& name,
                          const std::string& summary);

}  // namespace shudder::report
