// shudder.load / shudder.run in plain C++ (py_run.hpp).
#include "python/py_run.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <variant>

#include "app/output_size.hpp"
#include "studies/network_run.hpp"
#include "io/hdf5_run.hpp"
#include "io/network_scenario.hpp"
#include "io/output_safety.hpp"
#include "components/energy_guard.hpp"
#include "rig_models/model.hpp"
#include "studies/model_studies.hpp"

namespace shudder::python {

namespace {

// An error about an overridden key, said of the override ("overrides['drive.normal_force_N'] =
// -5: value -5 is out of range; allowed [0, 30000]"), not of a line of the scenario file the
// user did not write; other errors pass unchanged.
[[noreturn]] void rethrow_for_overrides(const io::InputError& e,
                                        const std::vector<std::pair<std::string, double>>& overrides) {
  const std::string what = e.what();
  for (const auto& [key, value] : overrides) {
    const std::string tag = "key '" + key + "': ";
    const auto at = what.find(tag);
    if (at == std::string::npos) continue;
    char number[32];
    std::snprintf(number, sizeof number, "%.10g", value);
    throw io::InputError("overrides['" + key + "'] = " + number, 0, "", what.substr(at + tag.size()));
  }
  throw e;
}

}  // namespace

io::Scenario load_with_overrides(const std::string& text_or_empty, const std::string& path,
                                 const std::vector<std::pair<std::string, double>>& overrides) {
  std::string text = text_or_empty.empty() ? io::load_scenario(path).text : text_or_empty;
  try {
    for (const auto& [key, value] : overrides) text = io::set_scenario_key(text, path, key, value);
    return io::load_scenario_text(text, path);
  } catch (const io::InputError& e) {
    if (overrides.empty()) throw;
    rethrow_for_overrides(e, overrides);
  }
}

RunOutcome run(const io::Scenario& scenario, const std::string& output, bool force) {
  RunOutcome out;
  out.warnings = scenario.warnings;
  const clutch::WetClutch clutch = scenario.make_clutch();
  if (!output.empty()) {
    // The checks of `shudder run` before simulating: not an input, an existing directory, a size.
    io::require_distinct_paths({{"scenario", scenario.path}, {"fluid file", scenario.fluid_path}},
                               {{"output", output}});
    io::require_output_directory(output);
    io::require_output_size(output, app::estimated_run_bytes(scenario),
                            std::to_string(app::estimated_samples(scenario)) + " samples x " +
                                std::to_string(app::recorded_channels(scenario)) + " channels x 8 bytes + snapshots",
                            force);
  }
  const auto t0 = std::chrono::steady_clock::now();
  out.recording = std::visit([&](const auto& m) { return rig_models::simulate(m, clutch); }, scenario.model);
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto analysis_warnings = std::visit(
      [&](const auto& m) { return studies::add_run_analysis(m, clutch, scenario.clutch.start_temp_C, out.recording); },
      scenario.model);
  out.warnings.insert(out.warnings.end(), analysis_warnings.begin(), analysis_warnings.end());
  if (!output.empty()) io::write_run_hdf5(output, out.recording, scenario.text, scenario.fluid_text);
  if (const std::string bad = components::energy_balance_violation(out.recording); !bad.empty())
    throw std::runtime_error("numerical failure: " + bad +
                             (output.empty() ? "" : "; the run is written to " + output + " for inspection") +
                             ", but its results cannot be trusted");
  return out;
}

RunOutcome run_network(const std::string& path, const std::vector<std::pair<std::string, double>>& overrides,
                       const std::string& output, std::string& name, std::string& text) {
  text = io::load_network_scenario(path).text;
  for (const auto& [key, value] : overrides) text = io::set_scenario_key(text, path, key, value);
  const io::NetworkScenario sc = io::load_network_scenario_text(text, path);
  name = sc.name;
  if (!output.empty()) {
    std::vector<io::RolePath> inputs{{"scenario", path}};
    for (const auto& f : sc.fluid_paths) inputs.push_back({"fluid file", f});
    io::require_distinct_paths(inputs, {{"output", output}});
    io::require_output_directory(output);
  }
  RunOutcome out;
  out.warnings = sc.warnings;
  const auto t0 = std::chrono::steady_clock::now();
  out.recording = studies::run_network(sc.spec).recording;
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!output.empty()) io::write_run_hdf5(output, out.recording, sc.text, sc.fluid_texts);
  if (const std::string bad = components::energy_balance_violation(out.recording); !bad.empty())
    throw std::runtime_error("numerical failure: " + bad + ", but its results cannot be trusted");
  return out;
}

}  // namespace shudder::python
