#include "fmu/network_fmu_package.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fmu/model_description_xml.hpp"
#include "fmu/network_variables.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/scenario.hpp"
#include "io/zip_archive.hpp"

namespace shudder::fmu {

namespace fs = std::filesystem;

namespace {

std::string read_binary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the network FMU library '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

NetworkFmuSummary write_network_fmu(const io::NetworkScenario& sc, double fixed_step_s,
                                    const NetworkFmuLibraries& libraries, const std::string& out) {
  // The description first: what the network cannot be as an FMU fails before anything is written.
  DescribedModel model;
  try {
    model = network_description(sc, fixed_step_s);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(sc.path, 0, "network", e.what());
  }
  const std::string xml = model_description_xml(model);

  // Each fluid's path relative to the scenario's folder, and how far the paths climb.
  const fs::path folder = fs::path(sc.path).parent_path();
  std::vector<std::pair<fs::path, std::string>> fluids;  // (relative path, text)
  std::size_t climb = 0;
  for (const auto& c : sc.spec.clutches) {
    if (c.law == components::ClutchSpec::Law::kPlain) continue;
    const fs::path given(c.wet.fluid_path);
    const fs::path rel = (folder.empty() ? given : given.lexically_relative(folder)).lexically_normal();
    if (rel.empty() || rel.is_absolute())
      throw io::InputError(sc.path, 0, "network." + c.name + ".clutch.fluid",
                           "the fluid file '" + c.wet.fluid_path +
                               "' is not reachable by a relative path from the scenario's "
                               "folder, so it cannot be packed; give it relative to the scenario");
    std::size_t up = 0;
    for (const auto& part : rel) {
      if (part != "..") break;
      ++up;
    }
    climb = std::max(climb, up);
    fluids.push_back({rel, c.wet.fluid_text});
  }
  fs::path scenario_dir = "network";
  for (std::size_t k = 0; k < climb; ++k) scenario_dir /= "level" + std::to_string(k + 1);
  const fs::path scenario_entry = scenario_dir / fs::path(sc.path).filename();

  std::vector<std::pair<std::string, std::string>> files;
  files.push_back({"modelDescription.xml", xml});
  NetworkFmuSummary s;
  files.push_back({std::string("binaries/linux64/") + kNetworkModelIdentifier + ".so", read_binary(libraries.linux64)});
  s.platforms.push_back("linux64");
  if (!libraries.win64.empty()) {
    files.push_back({std::string("binaries/win64/") + kNetworkModelIdentifier + ".dll", read_binary(libraries.win64)});
    s.platforms.push_back("win64");
  }
  std::ostringstream index;
  index.precision(17);
  index << "# Written by shudder export-fmu: the scenario the network FMU's library runs (fmu/network_fmu.cpp)\n"
        << "scenario = \"" << scenario_entry.generic_string() << "\"\nfixed_step_s = " << fixed_step_s << "\n";
  files.push_back({std::string("resources/") + kNetworkFmuIndex, index.str()});
  files.push_back({"resources/" + scenario_entry.generic_string(), sc.text});
  for (const auto& [rel, text] : fluids) {
    const std::string entry = "resources/" + (scenario_dir / rel).lexically_normal().generic_string();
    bool seen = false;
    for (const auto& f : files) seen = seen || f.first == entry;
    if (!seen) files.push_back({entry, text});
  }
  io::write_text_file_atomically(out, io::zip_stored(files));

  for (const auto& v : model.variables)
    (v.causality == Causality::kInput ? s.inputs : v.causality == Causality::kOutput ? s.outputs : s.parameters)++;
  s.guid = guid_of(xml);
  return s;
}

}  // namespace shudder::fmu
