#pragma once
// Network scenario files (type = "network", docs/formats/network_file.md) -> components::NetworkSpec.
// Strict like every scenario: unknown keys and component types are errors naming the file,
// line and key, with the nearest valid name; the network is built once at load, so a bad
// network (unknown node, massless node nothing fixes, gears over-constraining a loop, an
// undriven part, a clutch that can never load) fails here with the component's line, before
// anything runs.

#include <string>
#include <vector>

#include "components/network_spec.hpp"

namespace shudder::io {

struct NetworkScenario {
  std::string path, text, name, description;
  components::NetworkSpec spec;
  std::vector<std::string> fluid_paths;  // every wet clutch's fluid file, as resolved
  std::string fluid_texts;               // their texts, each after a "# file: PATH" line (stored in outputs)
  std::vector<std::string> warnings;
};

/// The `[scenario] type` of a scenario file ("prescribed_slip" when absent). Throws InputError
/// for an unreadable file or bad TOML.
std::string scenario_type(const std::string& path);
/// The same for scenario text (`path` names it in messages).
std::string scenario_type_of_text(const std::string& text, const std::string& path);
NetworkScenario load_network_scenario(const std::string& path);
NetworkScenario load_network_scenario_text(const std::string& text, const std::string& path);

}  // namespace shudder::io
