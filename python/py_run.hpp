#pragma once
// What the Python module's shudder.load / shudder.run do, in plain C++ (no Python types): a
// scenario's text with keys overridden by the sweep's own machinery (io::set_scenario_key, so
// the key names and the errors are those of `shudder sweep --set`), and one run exactly as
// `shudder run` makes it (simulate, the kind's run analysis, the energy-balance guard), the
// HDF5 file optional. Errors are the CLI's exceptions (app/guarded.hpp maps them).
#include <string>
#include <utility>
#include <vector>

#include "dynamics/recording.hpp"
#include "io/scenario.hpp"

namespace shudder::python {

/// A scenario's text from a file (`path`) or given as TOML (`path` then names it in messages
/// and is where a relative fluid path is resolved from), each override applied in order, then
/// loaded and checked as `shudder run` would.
io::Scenario load_with_overrides(const std::string& text_or_empty, const std::string& path,
                                 const std::vector<std::pair<std::string, double>>& overrides);

struct RunOutcome {
  dynamics::Recording recording;
  std::vector<std::string> warnings;  // the scenario's and the run analysis' warnings
  double wall_time_s = 0.0;           // the simulation alone
};

/// Runs the scenario as `shudder run` does; writes `output` (HDF5, atomic) unless empty.
/// An energy balance that does not close throws "numerical failure: ..." after writing.
RunOutcome run(const io::Scenario& scenario, const std::string& output, bool force);

/// A network scenario (docs/formats/network_file.md) run as `shudder run` runs it: the file's text
/// with each override applied (`network.COMPONENT.KEY`), the run, the HDF5 file unless `output`
/// is empty, the energy guard. `name` and `text` receive the scenario's name and final text.
RunOutcome run_network(const std::string& path, const std::vector<std::pair<std::string, double>>& overrides,
                       const std::string& output, std::string& name, std::string& text);

}  // namespace shudder::python
