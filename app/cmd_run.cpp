// `shudder run`: load a scenario, simulate, write HDF5 (and optionally a measured run: CSV, or
// its HDF5 form for a .h5/.hdf5 name), print a readable summary; optionally a report directory
// (summary.txt and plots).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "app/output_size.hpp"
#include "report/run_summary.hpp"
#include "core/units.hpp"
#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/measurement_csv.hpp"
#include "io/network_scenario.hpp"
#include "io/output_safety.hpp"
#include "report/plots.hpp"
#include "io/scenario.hpp"
#include "io/sweep_spec.hpp"
#include "components/energy_guard.hpp"
#include "rig_models/model.hpp"
#include "studies/model_studies.hpp"
#include "rig_models/realtime_run.hpp"

namespace shudder::app {

std::string run_scenario_text(const RunOptions& opt) {
  std::string text = io::read_scenario_text(opt.scenario);
  if (opt.sets.empty()) return text;
  std::vector<io::SweepAxis> sets;
  for (const auto& s : opt.sets) sets.push_back(io::parse_set_value(s));
  io::require_distinct_keys(sets);
  for (const auto& s : sets) text = io::set_scenario_key(text, opt.scenario, s.key, s.values.front());
  return text;
}

int run_command(const RunOptions& opt) {
  return guarded(opt.scenario, "simulation", [&]() -> int {
    const std::string text = run_scenario_text(opt);
    if (io::scenario_type_of_text(text, opt.scenario) == "network") return run_network_command(opt);
    // A misspelt --set key is an unknown key here, named with the nearest allowed one.
    const io::Scenario scenario = io::load_scenario_text(text, opt.scenario);
    for (const auto& w : scenario.warnings) std::cerr << "shudder: warning: " << w << "\n";
    if (const auto* ps = std::get_if<rig_models::PrescribedSlipModel>(&scenario.model);
        ps && opt.fixed_step_s > 0 && ps->settings.thermal_scheme == rig_models::ThermalScheme::kBdf2)
      std::cerr << "shudder: warning: [solver] thermal_scheme = \"bdf2\" is for the adaptive run; --fixed-step hands "
                   "the heat to the thermal field every thermal_step_ms ("
                << ps->settings.thermal_step_s * 1e3
                << " ms) with backward Euler, whose time error grows with that step (set thermal_step_ms = 10 for "
                   "the real-time mode's documented accuracy, docs/realtime.md)\n";
    const clutch::WetClutch clutch = scenario.make_clutch();
    const std::string out = opt.output.empty() ? scenario.name + ".h5" : opt.output;

    // Before simulating: no output may replace an input or another output, every output's
    // directory must exist, and the run file must fit the size limit (unless --force).
    std::vector<io::RolePath> outputs{{"-o", out}};
    if (!opt.measurement.empty()) outputs.push_back({"--measurement", opt.measurement});
    if (!opt.report.empty()) outputs.push_back({"--report", opt.report});
    io::require_distinct_paths({{"scenario", opt.scenario}, {"fluid file", scenario.fluid_path}}, outputs);
    for (const auto& o : outputs) io::require_output_directory(o.path);
    io::require_output_size(out, estimated_run_bytes(scenario),
                            std::to_string(estimated_samples(scenario)) + " samples x " +
                                std::to_string(recorded_channels(scenario)) + " channels x 8 bytes + snapshots",
                            opt.force);

    const auto t0 = std::chrono::steady_clock::now();
    dynamics::Recording rec =
        opt.fixed_step_s > 0
            ? io::visit_kind(opt.scenario, "--fixed-step", scenario.model,
                             [&](const auto& m) { return rig_models::run_fixed_step(m, clutch, opt.fixed_step_s); })
            : std::visit([&](const auto& m) { return rig_models::simulate(m, clutch); }, scenario.model);
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The kind's extra analysis (the rig's stability map for `shudder plot`) goes into the recording.
    const std::vector<std::string> analysis_warnings = std::visit(
        [&](const auto& m) { return studies::add_run_analysis(m, clutch, scenario.clutch.start_temp_C, rec); },
        scenario.model);
    for (const auto& w : analysis_warnings) std::cerr << "shudder: warning: " << w << "\n";

    io::write_run_hdf5(out, rec, scenario.text, scenario.fluid_text);
    if (!opt.measurement.empty()) {
      // The rig's log, or a driveline coupling's sensors (rig_models/model.hpp).
      const rig_models::MeasuredExport exported =
          std::visit([&](const auto& km) { return rig_models::measured_run_export(km, rec); }, scenario.model);
      io::MeasurementOptions m;
      m.rig = exported.rig;
      m.sample_rate_Hz = opt.measurement_rate_Hz;
      m.noise = opt.noise;
      m.seed = opt.seed;
      io::describe_clutch(m, scenario.clutch, scenario.fluid.name);
      io::write_measurement(opt.measurement, exported.channels(rec), m);
    }
    // Energy accounts that do not close mean the numbers are wrong: a numerical failure (exit
    // 1), reported after the files are written so the user can inspect what went wrong.
    if (const std::string bad = components::energy_balance_violation(rec); !bad.empty())
      throw std::runtime_error("numerical failure: " + bad + "; the run is written to " + out +
                               " for inspection, but its results cannot be trusted");

    std::ostringstream summary;
    report::print_run_summary(summary, scenario, rec);
    summary << "Output: " << out;
    if (!opt.measurement.empty()) summary << ", " << opt.measurement;
    summary << "\n";
    std::cout << summary.str();
    if (!opt.report.empty() &&
        write_report_directory(opt.report, rec, scenario.name, summary.str(),
                               std::visit([](const auto& m) { return rig_models::has_rig_plots(m); }, scenario.model),
                               out) != 0)
      return 1;
    if (opt.profile) std::cout << "Profile: simulation wall time " << wall_s * 1e3 << " ms\n";
    return 0;
  });
}

}  // namespace shudder::app
