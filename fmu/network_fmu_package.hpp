#pragma once
// `shudder export-fmu` (docs/fmu.md "Your drivetrain as an FMU"): a network scenario packed as
// an FMI 2.0 co-simulation FMU around the generic network FMU library (fmu/network_fmu.cpp).
//
// Archive:
//   modelDescription.xml                    fmu/network_variables.hpp's description, content GUID
//   binaries/linux64/shudder_network.so     the library, as built
//   binaries/win64/shudder_network.dll      its MinGW-w64 build, when one is given
//   resources/network_fmu.toml              scenario = "network/…/NAME.toml", fixed_step_s = H
//   resources/network/…/NAME.toml           the scenario's text as read
//   resources/network/…                     each wet clutch's fluid file, at the scenario's relative path
// The scenario sits as many folders below resources/network/ as its fluid paths climb with
// "..", so every fluid lands inside resources/ where the scenario's own relative path finds it.
//
// Written through a temporary and renamed (io/atomic_file.hpp): a failure leaves no .fmu.

#include <string>
#include <vector>

#include "io/network_scenario.hpp"

namespace shudder::fmu {

struct NetworkFmuSummary {
  std::size_t inputs = 0, outputs = 0, parameters = 0;
  std::string guid;
  std::vector<std::string> platforms;  // the binaries/ folders packed: "linux64", "win64"
};

/// The network FMU library's builds to pack: the linux64 .so (required) and the win64 .dll ("":
/// none).
struct NetworkFmuLibraries {
  std::string linux64, win64;
};

/// Packs `sc` (loaded from sc.path) into `out`; InputError naming the file and key for what
/// the FMU cannot hold (a fluid file given by an absolute path, names that collide), or naming
/// `out` when it cannot be written.
NetworkFmuSummary write_network_fmu(const io::NetworkScenario& sc, double fixed_step_s,
                                    const NetworkFmuLibraries& libraries, const std::string& out);

}  // namespace shudder::fmu
