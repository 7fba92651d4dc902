#pragma once
// Subcommands of the `shudder` CLI. Each returns the process exit code:
// 0 success, 2 bad input (io::InputError), 1 numerical or internal failure.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "components/network_spec.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/effect_registry.hpp"

namespace shudder::app {

struct RunOptions {
  std::string scenario;
  std::string output;                // HDF5 path; default "<scenario name>.h5"
  std::string measurement;           // measured-run CSV path; empty = none
  double measurement_rate_Hz = 0.0;  // 0 = the recording's rate
  bool noise = false;
  unsigned seed = 1;
  bool profile = false;
  std::string report;             // report directory (summary.txt + plots); empty = none
  bool force = false;             // write even above io::kMaxOutputBytesWithoutForce
  double fixed_step_s = 0.0;      // > 0: the fixed-step real-time mode (docs/realtime.md)
  std::vector<std::string> sets;  // KEY=VALUE overrides, the sweep's key names (io/sweep_spec.hpp)
};
int run_command(const RunOptions& options);
/// The scenario file's text with `run --set` applied (the sweep's parser and key setter); the
/// file's own text, comments kept, when nothing is set.
std::string run_scenario_text(const RunOptions& options);
/// `run` on a type = "network" scenario (app/cmd_run_network.cpp); run_command dispatches to it.
int run_network_command(const RunOptions& options);
/// `--fixed-step H` on a network (dynamics/simulation.hpp "Fixed-step mode"): the duration, the
/// thermal step (`wet`: the network has a wet clutch) and the sample interval are whole numbers
/// of steps, so every step is H and every sample and thermal update falls on a step's end.
/// InputError naming opt.scenario and the key otherwise.
void require_whole_steps(const RunOptions& opt, const components::NetworkSettings& s, bool wet);
/// `run --report DIR`: the report directory (report/plots.hpp) with a line saying so; a report
/// that fails after the run was written is exit code 1 with a line naming `run_file`.
int write_report_directory(const std::string& dir, const dynamics::Recording& rec, const std::string& name,
                           const std::string& summary, bool rig_plots, const std::string& run_file);

struct ExportFmuOptions {
  std::string scenario;
  std::string output;          // the .fmu; default "<scenario name>.fmu"
  double fixed_step_s = 1e-4;  // the FMU's internal step (its parameter fixed_step_s' start)
};
/// `export-fmu` (app/cmd_export_fmu.cpp, docs/fmu.md "Your drivetrain as an FMU").
int export_fmu_command(const ExportFmuOptions& options);

struct ConvergenceOptions {
  std::string scenario;
  double factor = 4.0;  // every exposed numerical step divided by this
};
/// `convergence` (app/cmd_convergence.cpp): exit 0 converged, 3 not converged.
int convergence_command(const ConvergenceOptions& options);

struct ModesOptions {
  std::string scenario;
  std::string run;  // a driveline run's HDF5 file: linearise at its mean operating point
};
int modes_command(const ModesOptions& options);

struct SweepOptions {
  std::string scenario;
  std::vector<std::string> sets;  // KEY=START:STOP:STEP or KEY=V1,V2,...
  unsigned jobs = 0;              // 0 = all cores
  std::string output;
  bool quiet = false;
  bool keep_parts = false;  // keep OUT.h5.parts/ after assembling (default: remove)
  std::string report;       // report directory (summary.txt + sweep.png); empty = none
  bool force = false;       // write even above io::kMaxOutputBytesWithoutForce
  bool mpi = false;         // run the cases on the MPI ranks (mpirun; app/mpi_sweep.hpp)
};
int sweep_command(const SweepOptions& options);

struct ScreenOptions {
  std::string fluid;        // fluid TOML
  std::string rig;          // rig scenario TOML; empty = default rigs (100, 300, 500 Hz bars)
  double load_N = 20000.0;  // normal load of the indices and maps
  std::string temps;        // "40,80,120"; empty = 40/80/120 °C where the data reach
  std::string json;         // JSON output path; empty = none
};
/// `screen` (app/cmd_screen.cpp): exit 0 judged, 3 not judged (no index computed).
int screen_command(const ScreenOptions& options);

struct PlotOptions {
  std::string file;    // run or sweep HDF5
  std::string what;    // torque|temperature|spectrum|spectrogram|stability_map|sweep
  std::string output;  // .png or .svg
};
int plot_command(const PlotOptions& options);

struct ValidateOptions {
  std::string scenarios_dir = "scenarios";
  std::string docs_dir = "docs";
  bool plots = true;
};
int validate_command(const ValidateOptions& options);

struct DiagnoseOptions {
  std::string model;                                                         // scenario TOML: the baseline model
  std::vector<std::string> runs;                                             // measured runs (CSV or HDF5)
  std::string json;                                                          // diagnosis JSON path; empty = none
  std::string report;                                                        // report directory; empty = none
  unsigned jobs = 0;                                                         // 0 = all cores
  int max_effects = static_cast<int>(rig_models::effect_registry().size());  // added at most (default: all)
  std::string tolerance;          // "torque_Nm=0.5,temp_C=2": model-form tolerance per channel
  std::string write_model;        // the baseline scenario with the named effects on; empty = none
  std::vector<std::string> maps;  // --map: the runs are a logger's CSV files (app/cmd_import.cpp)
  std::string mapping;            // --mapping: the same from a mapping file; empty = none
  std::string clutch;             // --clutch: a network's wet clutch; empty = the runs' metadata or the only one
  bool trust_units = false;       // --trust-units: skip the checks that values look like their units
};
int diagnose_command(const DiagnoseOptions& options);

struct CharacteriseOptions {
  std::vector<std::string> runs;           // measured runs (CSV or HDF5)
  std::string output;                      // fluid TOML written
  std::string json;                        // FIT.json; empty = none
  std::string report;                      // report directory; empty = none
  std::string law = "maki";                // maki | linear | table
  std::string compensation = "quadratic";  // none | linear | quadratic | piecewise
  double alpha_per_C = NAN;                // linear compensation: given alpha (NaN = fit it)
  std::string temperature_channel = "temp_C";
  std::string radius = "model";  // model | uniform_wear | uniform_pressure
  double mean_radius_mm = 46.0, inner_radius_mm = 38.1, outer_radius_mm = 56.4;
  int interfaces = 1;
  double bearing_drag_mu = 0.0;
  double temp_tolerance_C = 3.0;
  int min_ramps = 2;
  double linear_load_N = 20000.0;
  std::string row_temps, node_rpm;  // comma lists; empty = from the data / Paper D nodes
  std::string name;                 // fluid name; empty = output file stem
  double nu40_cSt = 0.0, nu100_cSt = 0.0;
  double breakaway_ratio = NAN;   // NaN: measured from ramps that start at rest, else 1
  std::string method = "sensor";  // sensor | inverse (replayed through the model)
  std::string model;  // the model the fluid is for: its clutch's radius; inverse: replayed; empty = Paper G defaults
  int inverse_iterations = 8;     // inverse: law updates per pass before "did not converge"
  std::vector<std::string> maps;  // --map: the runs are a logger's CSV files (app/cmd_import.cpp)
  std::string mapping;            // --mapping: the same from a mapping file; empty = none
  bool hot_row = true;            // a row at the hottest temperature the ramps reach (--no-hot-row: none)
  bool trust_units = false;       // --trust-units: skip the checks that values look like their units
};
int characterise_command(const CharacteriseOptions& options);

struct ImportOptions {
  std::string logger;              // the logger's CSV
  std::string output;              // measured run written (CSV, or HDF5 for .h5/.hdf5)
  std::vector<std::string> maps;   // SOURCE=TARGET:UNIT (io/import_mapping.hpp)
  std::string mapping;             // mapping file (TOML); empty = none
  std::vector<std::string> metas;  // KEY=VALUE metadata
  std::string delimiter = "auto";  // auto | , | ; | tab
  std::string decimal = "auto";    // auto | . | ,
  bool trust_units = false;        // skip the unit plausibility checks
};
/// `import` (app/cmd_import.cpp): a logger's CSV written as a measured run.
int import_command(const ImportOptions& options);

struct CompareOptions {
  std::vector<std::string> fluids;  // fluid TOML files
  std::vector<std::string> rigs;    // rig scenarios; empty = the screening's default rigs
  std::string temps;                // "30,60,90"; empty = 30, 60, 90 °C
  double load_N = 20000.0;
  double viscosity_cSt = 10.0;  // equal-viscosity comparison (Paper E Table 5)
  std::string json, report;
};
int compare_command(const CompareOptions& options);

}  // namespace shudder::app
