// shudder: command-line entry. Argument parsing and dispatch only; no physics here.
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "app/commands.hpp"
#include "app/mpi_sweep.hpp"

namespace {

// CLI11's message with any line breaks folded, so the error stays one line.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace shudder::app;
  CLI::App app{"shudder: stick-slip and shudder in wet-clutch drivetrains"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("shudder ") + SHUDDER_BUILD_VERSION);

  RunOptions run;
  auto* run_cmd = app.add_subcommand("run", "Run a scenario; write HDF5 and print a summary");
  run_cmd->add_option("scenario", run.scenario, "Scenario file (TOML)")->required();
  run_cmd->add_option("--set", run.sets,
                      "KEY=VALUE: set a numeric scenario key for this run, as `sweep --set` "
                      "names it (repeatable)");
  run_cmd->add_option("-o,--output", run.output, "HDF5 output (default: <scenario name>.h5)");
  run_cmd->add_option("--measurement", run.measurement, "Also write the sensor signals as a measured-run CSV");
  run_cmd
      ->add_option("--sample-rate", run.measurement_rate_Hz,
                   "Sample rate of the measured-run CSV, Hz (default: recording rate)")
      ->check(CLI::Range(1e-3, 1e6));
  run_cmd->add_flag("--noise", run.noise, "Add sensor noise of the rig's stated accuracy");
  run_cmd->add_option("--seed", run.seed, "Seed of the sensor noise (deterministic)");
  run_cmd->add_flag("--profile", run.profile, "Print the simulation's wall time");
  run_cmd->add_option("--report", run.report,
                      "Also write a report directory: summary.txt, the key plots (PNG) and index.html to open");
  run_cmd->add_flag("--force", run.force, "Write the output even if its estimated size exceeds 2 GB");
  run_cmd
      ->add_option("--fixed-step", run.fixed_step_s,
                   "Run with the fixed-step real-time stepper at this step, s (docs/realtime.md)")
      ->check(CLI::Range(1e-7, 1.0));  // a step from 0.1 µs to 1 s

  ExportFmuOptions export_fmu;
  auto* fmu_cmd = app.add_subcommand(
      "export-fmu", "Pack a network scenario as an FMI 2.0 co-simulation FMU, linux64 and win64 (docs/fmu.md)");
  fmu_cmd->add_option("scenario", export_fmu.scenario, "Network scenario file (TOML, type = \"network\")")->required();
  fmu_cmd->add_option("-o,--output", export_fmu.output, "FMU written (default: <scenario name>.fmu)");
  fmu_cmd
      ->add_option("--fixed-step", export_fmu.fixed_step_s,
                   "The FMU's internal RK4 step, s (default 1e-4; as run --fixed-step)")
      ->check(CLI::Range(1e-7, 1.0));

  ConvergenceOptions convergence;
  auto* conv_cmd =
      app.add_subcommand("convergence",
                         "Re-run a scenario with its numerical steps divided and show whether its verdicts change "
                         "(exit 0 converged, 3 not)");
  conv_cmd->add_option("scenario", convergence.scenario, "Scenario file (TOML)")->required();
  conv_cmd->add_option("--factor", convergence.factor, "Divide every exposed step by this (default 4)")
      ->check(CLI::Range(1.5, 100.0));

  ModesOptions modes;
  auto* modes_cmd = app.add_subcommand("modes", "Natural frequencies and mode shapes of a rig or driveline scenario");
  modes_cmd->add_option("scenario", modes.scenario, "Scenario file (TOML, type = \"rig\" or \"driveline\")")
      ->required();
  modes_cmd->add_option("--run", modes.run,
                        "A driveline run of this scenario (HDF5 from `shudder run`): linearise at the run's mean "
                        "operating point, as its summary's shuffle mode is");

  SweepOptions sweep;
  auto* sweep_cmd = app.add_subcommand("sweep", "Run a scenario over a grid of key values, in parallel");
  sweep_cmd->add_option("scenario", sweep.scenario, "Scenario file (TOML)")->required();
  sweep_cmd->add_option("--set", sweep.sets, "KEY=START:STOP:STEP or KEY=V1,V2,... (repeatable)")->required();
  sweep_cmd->add_option("--jobs", sweep.jobs, "Parallel cases (default: all cores)")->check(CLI::Range(1u, 1024u));
  sweep_cmd->add_option("-o,--output", sweep.output, "Sweep HDF5 file")->required();
  sweep_cmd->add_flag("--quiet", sweep.quiet, "No progress bar or summary");
  sweep_cmd->add_flag("--keep-parts", sweep.keep_parts, "Keep the per-case files (OUT.h5.parts/)");
  sweep_cmd->add_option("--report", sweep.report,
                        "Also write a report directory: summary.txt, sweep.png and index.html to open");
  sweep_cmd->add_flag("--force", sweep.force, "Write the output even if its estimated size exceeds 2 GB");
  sweep_cmd->add_flag("--mpi", sweep.mpi,
                      "Run the cases on every MPI rank (mpirun -np N shudder sweep ...; docs/mpi.md)");

  ScreenOptions screen;
  auto* screen_cmd = app.add_subcommand("screen", "Screen a fluid's friction data for vibration risk");
  screen_cmd->add_option("fluid", screen.fluid, "Fluid file (TOML)")->required();
  screen_cmd->add_option("--rig", screen.rig,
                         "Rig scenario (TOML, type = \"rig\"); default: rigs with 100, 300, 500 Hz bars");
  screen_cmd->add_option("--load-N", screen.load_N, "Normal load, N (default 20000)");
  screen_cmd->add_option("--temps", screen.temps,
                         "Temperatures, degC, comma-separated (default 40,80,120 where the data reach)");
  screen_cmd->add_option("--json", screen.json, "Write the results as JSON");

  PlotOptions plot;
  auto* plot_cmd = app.add_subcommand("plot", "Plot a run or sweep file (PNG or SVG, via gnuplot)");
  plot_cmd->add_option("file", plot.file, "Run or sweep HDF5 file")->required();
  plot_cmd->add_option("--what", plot.what, "torque|temperature|spectrum|spectrogram|stability_map|sweep|coupling")
      ->required()
      ->check(
          CLI::IsMember({"torque", "temperature", "spectrum", "spectrogram", "stability_map", "sweep", "coupling"}));
  plot_cmd->add_option("-o,--output", plot.output, "Image to write (.png or .svg)")->required();

  ValidateOptions validate;
  auto* val_cmd = app.add_subcommand(
      "validate", "Run the Paper G / Paper B calibration cases; regenerate docs/validation.md and plots");
  val_cmd->add_option("--scenarios", validate.scenarios_dir, "Folder holding the scenarios");
  val_cmd->add_option("--docs", validate.docs_dir, "Folder to write validation.md and PNGs into");
  val_cmd->add_flag("!--no-plots", validate.plots, "Skip the PNG plots (no gnuplot needed)");

  DiagnoseOptions diagnose;
  auto* diag_cmd =
      app.add_subcommand("diagnose", "Find where a model and measured runs disagree and which effect is missing");
  diag_cmd->add_option("model", diagnose.model, "Scenario file (TOML): the baseline model")->required();
  diag_cmd->add_option("runs", diagnose.runs, "Measured runs (CSV or HDF5, docs/formats/measured_run.md)")->required();
  diag_cmd->add_option("--clutch", diagnose.clutch,
                       "A network scenario's wet clutch the runs are of (default: the runs' `clutch` metadata, or the "
                       "network's only wet clutch)");
  diag_cmd->add_option("--json", diagnose.json, "Write the diagnosis as JSON (shudder-diagnosis/1)");
  diag_cmd->add_option("--report", diagnose.report,
                       "Also write a report directory: summary, candidate table, plots, index.html");
  diag_cmd->add_option("--jobs", diagnose.jobs, "Parallel fits (default: all cores)")->check(CLI::Range(1u, 1024u));
  const int effect_count = static_cast<int>(shudder::rig_models::effect_registry().size());
  diag_cmd
      ->add_option("--max-effects", diagnose.max_effects,
                   "Add at most this many effects (default " + std::to_string(effect_count) + ": no limit)")
      ->check(CLI::Range(0, effect_count));
  diag_cmd->add_option("--tolerance", diagnose.tolerance,
                       "Model-form tolerance per channel, e.g. torque_Nm=0.5,temp_C=2 (signal units; "
                       "docs/diagnosis.md)");
  diag_cmd->add_option("--write-model", diagnose.write_model,
                       "Write the baseline scenario with the named effects on at their fitted parameters");
  diag_cmd->add_option("--map", diagnose.maps,
                       "The runs are a logger's CSV: SOURCE=TARGET:UNIT as `shudder import --map`");
  diag_cmd->add_option("--mapping", diagnose.mapping,
                       "The runs are a logger's CSV: its mapping file (shudder import --mapping)");
  diag_cmd->add_flag("--trust-units", diagnose.trust_units,
                     "Skip the checks that a logger's values look like their units (as shudder import --trust-units)");

  CharacteriseOptions characterise;
  auto* char_cmd = app.add_subcommand("characterise",
                                      "Fit a fluid's friction law to measured speed ramps (docs/characterisation.md)");
  char_cmd->add_option("runs", characterise.runs, "Measured runs (CSV or HDF5, docs/formats/measured_run.md)")
      ->required();
  char_cmd->add_option("-o,--output", characterise.output, "Fluid file written (TOML)")->required();
  char_cmd->add_option("--json", characterise.json, "Write the fit statistics (shudder-characterisation/1)");
  char_cmd->add_option("--report", characterise.report, "Write a report directory (summary, plots, index.html)");
  char_cmd->add_option("--law", characterise.law, "maki (Paper G eq. 13), linear (Papers B/C/E) or table")
      ->check(CLI::IsMember({"maki", "linear", "table"}));
  char_cmd
      ->add_option("--compensation", characterise.compensation,
                   "Temperature compensation: none, linear (Papers B/C), quadratic (Paper D) or piecewise (linear in T "
                   "between the rows, all samples at once)")
      ->check(CLI::IsMember({"none", "linear", "quadratic", "piecewise"}));
  char_cmd->add_option("--alpha", characterise.alpha_per_C, "Linear compensation's alpha, 1/degC (default: fitted)")
      ->check(CLI::Range(-0.1, 0.1));
  char_cmd->add_option("--temperature-channel", characterise.temperature_channel, "temp_C or ir_temp_C")
      ->check(CLI::IsMember({"temp_C", "ir_temp_C"}));
  char_cmd
      ->add_option("--radius", characterise.radius,
                   "Friction radius: model (default: where the clutch model of --model, or the default clutch, "
                   "produces torque), uniform_wear (thesis: --mean-radius-mm) or uniform_pressure "
                   "(--inner/--outer-radius-mm)")
      ->check(CLI::IsMember({"model", "uniform_wear", "uniform_pressure"}));
  char_cmd->add_option("--mean-radius-mm", characterise.mean_radius_mm, "Uniform-wear radius, mm (default 46)")
      ->check(CLI::Range(1.0, 1000.0));
  char_cmd->add_option("--inner-radius-mm", characterise.inner_radius_mm, "Friction annulus inner radius, mm (38.1)")
      ->check(CLI::Range(0.0, 1000.0));
  char_cmd->add_option("--outer-radius-mm", characterise.outer_radius_mm, "Friction annulus outer radius, mm (56.4)")
      ->check(CLI::Range(1.0, 1000.0));
  char_cmd->add_option("--interfaces", characterise.interfaces, "Sliding interfaces (default 1)")
      ->check(CLI::Range(1, 100));
  char_cmd
      ->add_option("--bearing-drag-mu", characterise.bearing_drag_mu,
                   "Bearing drag as an equivalent mu, subtracted (thesis rig: 0.005; default 0)")
      ->check(CLI::Range(0.0, 0.1));
  char_cmd
      ->add_option("--temp-tolerance", characterise.temp_tolerance_C,
                   "Ramps starting within this many degC share a row (default 3)")
      ->check(CLI::Range(0.1, 50.0));
  char_cmd->add_option("--min-ramps", characterise.min_ramps, "Fewest ramps per row (default 2)")
      ->check(CLI::Range(1, 1000));
  char_cmd->add_option("--linear-load", characterise.linear_load_N, "Load of a linear law's rows, N (20000)")
      ->check(CLI::Range(1.0, 1e7));
  char_cmd->add_option("--row-temps", characterise.row_temps, "Row temperatures, degC, e.g. 30,50,70");
  char_cmd->add_option("--node-rpm", characterise.node_rpm, "Node speeds, rpm (default 1,5,10,...,100)");
  char_cmd->add_option("--name", characterise.name, "Fluid name (default: the output's stem)");
  char_cmd->add_option("--nu40-cSt", characterise.nu40_cSt, "Kinematic viscosity at 40 degC, cSt")->required();
  char_cmd->add_option("--nu100-cSt", characterise.nu100_cSt, "Kinematic viscosity at 100 degC, cSt")->required();
  char_cmd
      ->add_option("--breakaway-ratio", characterise.breakaway_ratio,
                   "mu_s / mu_k(v_min) (default: measured from ramps that start at rest, else 1)")
      ->check(CLI::Range(0.5, 3.0));
  char_cmd
      ->add_option("--method", characterise.method,
                   "sensor (compensate with the temperature channel) or inverse (replay through the clutch and "
                   "thermal model; both reported)")
      ->check(CLI::IsMember({"sensor", "inverse"}));
  char_cmd->add_option("--model", characterise.model,
                       "Scenario of the model the fluid is for: its clutch's friction "
                       "radius (--radius model) and, with --method inverse, the clutch "
                       "and thermal model that replay the runs (default: Paper G's clutch)");
  char_cmd->add_flag("--hot-row,!--no-hot-row", characterise.hot_row,
                     "Add a row at the hottest temperature the ramps reach, from the top row's ramps compensated "
                     "to it (default; Maki and table laws). --no-hot-row: the law holds the top row's mu above it");
  char_cmd
      ->add_option("--inverse-iterations", characterise.inverse_iterations,
                   "--method inverse: law updates per pass before it counts as not converged (default 8)")
      ->check(CLI::Range(1, 100));

  char_cmd->add_option("--map", characterise.maps,
                       "The runs are a logger's CSV: SOURCE=TARGET:UNIT as `shudder import --map`");
  char_cmd->add_option("--mapping", characterise.mapping,
                       "The runs are a logger's CSV: its mapping file (shudder import --mapping)");
  char_cmd->add_flag("--trust-units", characterise.trust_units,
                     "Skip the checks that the runs' values look like their units (as shudder import --trust-units)");

  CompareOptions compare;
  auto* cmp_cmd =
      app.add_subcommand("compare", "Compare fluids: indices, equal viscosity, breakaway, rig margins, ranking");
  cmp_cmd->add_option("fluids", compare.fluids, "Fluid files (TOML)")->required();
  cmp_cmd->add_option("--rig", compare.rigs, "Rig scenario(s) (type = \"rig\"); default: 100, 300, 500 Hz bars");
  cmp_cmd->add_option("--temps", compare.temps, "Temperatures, degC, comma-separated (default 30,60,90)");
  cmp_cmd->add_option("--load-N", compare.load_N, "Normal load, N (default 20000)");
  cmp_cmd->add_option("--viscosity-cSt", compare.viscosity_cSt, "Equal-viscosity comparison, cSt (default 10)")
      ->check(CLI::Range(0.5, 10000.0));
  cmp_cmd->add_option("--json", compare.json, "Write the comparison as JSON (shudder-compare/1)");
  cmp_cmd->add_option("--report", compare.report,
                      "Write a report directory (summary, overlaid mu-v plots, index.html)");

  ImportOptions import;
  auto* imp_cmd =
      app.add_subcommand("import", "Turn a test-rig logger's CSV into a measured run (docs/formats/import_mapping.md)");
  imp_cmd->add_option("logger", import.logger, "Logger CSV (comma, semicolon or tab; decimal point or comma)")
      ->required();
  imp_cmd->add_option("-o,--output", import.output, "Measured run written (CSV; HDF5 for .h5)")->required();
  imp_cmd->add_option("--map", import.maps,
                      "SOURCE=TARGET:UNIT, e.g. force=normal_force_N:kN or time=time_s:ms (repeatable)");
  imp_cmd->add_option("--mapping", import.mapping, "Mapping file (TOML) of a rig's logger: [columns], [metadata]");
  imp_cmd->add_option("--meta", import.metas, "KEY=VALUE metadata, e.g. oil_flow_ml_min=200 (repeatable)");
  imp_cmd->add_option("--delimiter", import.delimiter, "auto (default), ',', ';' or tab");
  imp_cmd->add_option("--decimal", import.decimal, "auto (default), '.' or ','");
  imp_cmd->add_flag("--trust-units", import.trust_units, "Skip the checks that values look like their units");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version (exit code 0) print as CLI11 prints them; every usage error is ONE
    // line with our prefix and a pointer to the help, exit 2.
    if (e.get_exit_code() == 0) return app.exit(e);
    const auto used = app.get_subcommands();
    std::cerr << "shudder: error: " << one_line(e.what()) << " (see shudder "
              << (used.empty() ? std::string() : used.front()->get_name() + " ") << "--help)\n";
    return 2;
  }
  // Options that act on another one's output would be silently ignored without it.
  if (*run_cmd && run_cmd->count("--seed") > 0 && !run.noise) {
    std::cerr << "shudder: error: --seed sets the sensor noise; give --noise too\n";
    return 2;
  }
  for (const char* measured_only : {"--sample-rate", "--noise"})
    if (*run_cmd && run_cmd->count(measured_only) > 0 && run.measurement.empty()) {
      std::cerr << "shudder: error: " << measured_only
                << " applies to the measured run; give --measurement FILE.csv too\n";
      return 2;
    }
  if (*run_cmd) return run_command(run);
  if (*fmu_cmd) return export_fmu_command(export_fmu);
  if (*val_cmd) return validate_command(validate);
  if (*modes_cmd) return modes_command(modes);
  if (*conv_cmd) return convergence_command(convergence);
  if (*sweep_cmd && sweep.mpi) mpi::relaunch_with_mpi(argv);  // shudder-mpi (app/mpi_sweep.hpp)
  if (*sweep_cmd) return sweep_command(sweep);
  if (*screen_cmd) return screen_command(screen);
  if (*plot_cmd) return plot_command(plot);
  if (*diag_cmd) return diagnose_command(diagnose);
  if (*char_cmd) return characterise_command(characterise);
  if (*cmp_cmd) return compare_command(compare);
  if (*imp_cmd) return import_command(import);
  return 2;
}
