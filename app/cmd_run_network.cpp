// `shudder run` on a network scenario (docs/formats/network_file.md): load and check the network,
// simulate every clutch, write the HDF5 run file and print the summary with each clutch's verdict.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "app/commands.hpp"
#include "components/network_builder.hpp"
#include "studies/network_run.hpp"
#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/measurement_csv.hpp"
#include "rig_models/rig_names.hpp"
#include "io/network_scenario.hpp"
#include "io/output_safety.hpp"
#include "report/network_summary.hpp"
#include "components/energy_guard.hpp"

namespace shudder::app {

namespace {

// `--measurement RUN.csv` writes RUN.CLUTCH.csv for each wet clutch (the extension kept).
std::string measurement_path(const std::string& given, const std::string& clutch) {
  const std::filesystem::path p(given);
  return (p.parent_path() / (p.stem().string() + "." + clutch + p.extension().string())).string();
}

// One wet clutch's channels as a measured run (io/measurement_csv.hpp): its slip as speed_rpm,
// its friction torque, its normal force, its thermocouple.
void write_clutch_measurement(const RunOptions& opt, const components::ClutchSpec& c, const dynamics::Recording& rec) {
  dynamics::Recording m;
  const auto copy = [&](const std::string& from, const char* to) {
    const auto* s = rec.find(from);
    if (!s) throw std::logic_error("network run: no channel " + from);
    m.signals.push_back({to, s->units, s->values});
  };
  copy("time_s", "time_s");
  copy(c.name + ".slip_rpm", "speed_rpm");
  copy(c.name + ".normal_force_N", "normal_force_N");
  copy(c.name + ".torque_Nm", "torque_Nm");
  copy(c.name + ".temp_C", "temp_C");
  io::MeasurementOptions o;
  o.rig = std::string(rig_models::kNetworkClutchRig);
  o.clutch = c.name;
  o.sample_rate_Hz = opt.measurement_rate_Hz;
  o.noise = opt.noise;
  o.seed = opt.seed;
  io::describe_clutch(o, components::pack_params(c), c.wet.fluid.name);
  io::write_measurement(measurement_path(opt.measurement, c.name), m, o);
}

}  // namespace

void require_whole_steps(const RunOptions& opt, const components::NetworkSettings& s, bool wet) {
  const double h = opt.fixed_step_s;
  const auto check = [&](double span_s, const char* key, const char* what) {
    const double n = std::round(span_s / h);
    if (n >= 1.0 && std::abs(span_s / h - n) <= 1e-9 * n) return;
    std::ostringstream line;
    line << "--fixed-step " << h << " s: " << what << " (" << span_s
         << " s) must be a whole number of fixed steps; choose a step that divides it";
    throw io::InputError(opt.scenario, 0, key, line.str());
  };
  if (!(h > 0) || !std::isfinite(h))
    throw io::InputError(opt.scenario, 0, "--fixed-step", "the step must be a number > 0 (s), e.g. 1e-4");
  check(s.duration_s, "scenario.duration_s", "the duration");
  if (wet) check(s.thermal_step_s, "solver.thermal_step_ms", "the thermal step");
  check(1.0 / s.sample_rate_Hz, "output.sample_rate_Hz", "the sample interval");
}

int run_network_command(const RunOptions& opt) {
  io::NetworkScenario sc = io::load_network_scenario_text(run_scenario_text(opt), opt.scenario);
  for (const auto& w : sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
  if (opt.fixed_step_s != 0) {
    const bool wet = std::any_of(sc.spec.clutches.begin(), sc.spec.clutches.end(),
                                 [](const auto& c) { return c.law != components::ClutchSpec::Law::kPlain; });
    require_whole_steps(opt, sc.spec.settings, wet);
    sc.spec.settings.integrator.fixed_step_s = opt.fixed_step_s;
  }
  const std::string out = opt.output.empty() ? sc.name + ".h5" : opt.output;
  std::vector<io::RolePath> inputs{{"scenario", opt.scenario}};
  for (const auto& f : sc.fluid_paths) inputs.push_back({"fluid file", f});
  std::vector<io::RolePath> outputs{{"-o", out}};
  if (!opt.report.empty()) outputs.push_back({"--report", opt.report});
  std::vector<const components::ClutchSpec*> measured;  // the wet clutches, one measured run each
  for (const auto& c : sc.spec.clutches)
    if (c.law != components::ClutchSpec::Law::kPlain) measured.push_back(&c);
  if (!opt.measurement.empty()) {
    if (measured.empty())
      throw io::InputError(opt.scenario, 0, "--measurement",
                           "a measured run needs a clutch's temperature sensor; this network has no wet clutch "
                           "(its plain clutches' channels are in the HDF5 run file)");
    for (const auto* c : measured) outputs.push_back({"--measurement", measurement_path(opt.measurement, c->name)});
  }
  io::require_distinct_paths(inputs, outputs);
  for (const auto& o : outputs) io::require_output_directory(o.path);
  const double samples = sc.spec.settings.duration_s * sc.spec.settings.sample_rate_Hz;
  if (samples > 5e7)
    throw io::InputError(opt.scenario, 0, "output.sample_rate_Hz",
                         "duration x sample rate asks for " + std::to_string(static_cast<long>(samples)) +
                             " samples per channel; lower the rate (at most 5e7 samples)");

  const auto t0 = std::chrono::steady_clock::now();
  const studies::NetworkRun run = studies::run_network(sc.spec);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_run_hdf5(out, run.recording, sc.text, sc.fluid_texts);
  if (const std::string bad = components::energy_balance_violation(run.recording); !bad.empty())
    throw std::runtime_error("numerical failure: " + bad + "; the run is written to " + out +
                             " for inspection, but its results cannot be trusted");
  if (!opt.measurement.empty())
    for (const auto* c : measured) write_clutch_measurement(opt, *c, run.recording);
  std::ostringstream summary;
  report::print_network_summary(summary, sc, run);
  summary << "Output: " << out;
  if (!opt.measurement.empty())
    for (const auto* c : measured) summary << ", " << measurement_path(opt.measurement, c->name);
  summary << "\n";
  std::cout << summary.str();
  // summary.txt, verdict.json and the plots of `shudder plot` (docs/plots.md).
  if (!opt.report.empty() && write_report_directory(opt.report, run.recording, sc.name, summary.str(), false, out) != 0)
    return 1;
  if (opt.profile) std::cout << "Profile: simulation wall time " << wall_s * 1e3 << " ms\n";
  return 0;
}

}  // namespace shudder::app
