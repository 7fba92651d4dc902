#pragma once
// The plots of `shudder plot` and of the report directories of `shudder run` / `sweep`
// (docs/plots.md), built from what a run or sweep file holds and drawn by report/gnuplot:
//
//   torque         torque_Nm (and clutch_torque_Nm) vs time, sliding speed in its own panel,
//                  detail panels of an oscillating run (report/time_plots.hpp)
//   temperature    temp_C, ir_temp_C, sump_temp_C, interface_max_temp_C vs time
//   coupling       a driveline's coupling torque and slip (report/time_plots.hpp)
//   spectrum       Hann-windowed amplitude spectrum of the judged torque (mean removed) over
//                  the oscillating part the detector measured and over the whole record, log
//                  amplitude, the detected shudder peak (analysis/shudder_detection) marked
//                  and labelled with both amplitudes
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
#include "report/report_directory.hpp"
#include "report/time_plots.hpp"
#include "io/hdf5_sweep.hpp"

namespace shudder::report {

enum class PlotKind { kTorque, kTemperature, kSpectrum, kSpectrogram, kStabilityMap, kSweep, kCoupling };

/// The names accepted by --what, in PlotKind order.
const std::vector<std::string>& plot_kind_names();
std::optional<PlotKind> parse_plot_kind(std::string_view name);

/// The `[scenario] name` of a scenario text; `fallback` if the text has none or does not parse.
std::string scenario_name(const std::string& scenario_text, const std::string& fallback);

/// Builders: `name` titles the plot (the scenario's name), `source` names the data in errors.
/// The time histories (torque, coupling, temperature) are in report/time_plots.hpp.
Plot spectrum_plot(const dynamics::Recording& rec, const std::string& name, const std::string& source);
Plot spectrogram_plot(const dynamics::Recording& rec, const std::string& name, const std::string& source);
Plot stability_map_plot(const dynamics::Recording& rec, const std::string& name, const std::string& source);
MultiPlot sweep_plot(const io::SweepTable& table, const std::string& name, const std::string& source);

/// The figure of `kind` for a run recording (every kind but kSweep).
MultiPlot run_plot(PlotKind kind, const dynamics::Recording& rec, const std::string& name, const std::string& source);

/// Contour line(s) of `values` (n_x x n_y on the grid x, y) at `level` by marching squares:
/// one straight segment per grid cell the level crosses (linear interpolation along the cell
/// edges; saddles resolved by the cell's mean), segments separated by NaN points so the line
/// breaks between them. Cells with a non-finite corner are skipped. Empty if nothing crosses.
Series contour_series(const std::vector<double>& x, const std::vector<double>& y, const Eigen::MatrixXd& values,
                      double level, const std::string& label);

/// Reads the run or sweep file `h5_path` and writes the plot of `kind` to `out_path` (.png or
/// .svg). io::InputError when the file is unreadable or lacks what the plot needs.
void plot_file(const std::string& h5_path, PlotKind kind, const std::string& out_path);

}  // namespace shudder::report
