// `shudder run` on a network scenario (docs/network_format.md): load and check the network,
// simulate every clutch, write the HDF5 run file and print the summary with each clutch's verdict.
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "app/commands.hpp"
#include "components/network_run.hpp"
#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/network_scenario.hpp"
#include "io/output_safety.hpp"
#include "report/network_summary.hpp"
#include "rig_models/energy_guard.hpp"

namespace shudder::app {

int run_network_command(const RunOptions& opt) {
  const io::NetworkScenario sc = io::load_network_scenario(opt.scenario);
  for (const auto& w : sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
  if (opt.fixed_step_s > 0)
    throw io::InputError(opt.scenario, 0, "--fixed-step",
                         "the fixed-step mode runs the rig and the prescribed-slip clutch; a network runs adaptively "
                         "(remove --fixed-step)");
  if (!opt.measurement.empty())
    throw io::InputError(opt.scenario, 0, "--measurement",
                         "a network writes no measured-run file yet; read the clutches' channels from the HDF5 run file");
  if (!opt.report.empty())
    throw io::InputError(opt.scenario, 0, "--report",
                         "a network has no report directory yet; the summary is printed and the run is in the HDF5 file");
  const std::string out = opt.output.empty() ? sc.name + ".h5" : opt.output;
  std::vector<io::RolePath> inputs{{"scenario", opt.scenario}};
  for (const auto& f : sc.fluid_paths) inputs.push_back({"fluid file", f});
  io::require_distinct_paths(inputs, {{"-o", out}});
  io::require_output_directory(out);
  const double samples = sc.spec.settings.duration_s * sc.spec.settings.sample_rate_Hz;
  if (samples > 5e7)
    throw io::InputError(opt.scenario, 0, "output.sample_rate_Hz",
                         "duration x sample rate asks for " + std::to_string(static_cast<long>(samples)) +
                             " samples per channel; lower the rate (at most 5e7 samples)");

  const components::NetworkRun run = components::run_network(sc.spec);
  io::write_run_hdf5(out, run.recording, sc.text, sc.fluid_texts);
  if (const std::string bad = rig_models::energy_balance_violation(run.recording); !bad.empty())
    throw std::runtime_error("numerical failure: " + bad + "; the run is written to " + out +
                             " for inspection, but its results cannot be trusted");
  std::ostringstream summary;
  report::print_network_summary(summary, sc, run);
  summary << "Output: " << out << "\n";
  std::cout << summary.str();
  return 0;
}

}  // namespace shudder::app
