#include "io/fixed_model.hpp"

#include <filesystem>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/toml_reader.hpp"

namespace shudder::io {

namespace fs = std::filesystem;

namespace {

// `effects` switched on at their fitted parameters in the effect table `tables`.
void set_effects(toml::table& tables, const std::vector<analysis::FittedEffect>& effects) {
  for (const auto& e : effects) {
    if (!tables.contains(e.effect)) tables.insert(e.effect, toml::table{});
    auto* t = tables[e.effect].as_table();
    t->insert_or_assign("enabled", true);
    for (const auto& [key, value] : e.parameters) t->insert_or_assign(key, value);
  }
}

std::string with_header(const std::string& baseline_path, const toml::table& doc) {
  std::ostringstream os;
  os << "# Written by `shudder diagnose --write-model`: " << baseline_path << " with the effects it named\n"
     << "# switched on at their fitted parameters.\n"
     << doc << "\n";
  return os.str();
}

}  // namespace

std::string fixed_model_text(const Scenario& baseline, const std::vector<analysis::FittedEffect>& effects,
                             const std::string& out_path) {
  toml::table doc = TomlTable::parse_text(baseline.text, baseline.path);
  if (auto* clutch = doc["clutch"].as_table(); clutch && clutch->contains("fluid") && !baseline.fluid_path.empty()) {
    const fs::path out_dir = fs::absolute(fs::path(out_path)).parent_path();
    clutch->insert_or_assign("fluid", fs::relative(fs::absolute(baseline.fluid_path), out_dir).generic_string());
  }
  if (!effects.empty() && !doc.contains("effects")) doc.insert("effects", toml::table{});
  if (auto* tables = doc["effects"].as_table()) set_effects(*tables, effects);
  return with_header(baseline.path, doc);
}

std::string fixed_network_text(const NetworkScenario& baseline, const std::string& clutch,
                               const std::vector<analysis::FittedEffect>& effects, const std::string& out_path) {
  toml::table doc = TomlTable::parse_text(baseline.text, baseline.path);
  const fs::path out_dir = fs::absolute(fs::path(out_path)).parent_path();
  const fs::path base_dir = fs::absolute(fs::path(baseline.path)).parent_path();
  if (auto* network = doc["network"].as_table()) {
    // Every wet clutch's fluid, relative to the new file (a relative path was the baseline's).
    for (auto& [name, node] : *network) {
      auto* pack = node.as_table() ? (*node.as_table())["clutch"].as_table() : nullptr;
      if (!pack) continue;
      if (const auto fluid = (*pack)["fluid"].value<std::string>()) {
        const fs::path p = fs::path(*fluid).is_absolute() ? fs::path(*fluid) : base_dir / *fluid;
        pack->insert_or_assign("fluid", fs::relative(p.lexically_normal(), out_dir).generic_string());
      }
    }
    if (auto* c = (*network)[clutch].as_table(); c && !effects.empty()) {
      if (!c->contains("effects")) c->insert("effects", toml::table{});
      if (auto* tables = (*c)["effects"].as_table()) set_effects(*tables, effects);
    }
  }
  return with_header(baseline.path, doc);
}

void write_fixed_network(const NetworkScenario& baseline, const std::string& clutch,
                         const std::vector<analysis::FittedEffect>& effects, const std::string& out_path) {
  write_text_file_atomically(out_path, fixed_network_text(baseline, clutch, effects, out_path));
}

void write_fixed_model(const Scenario& baseline, const std::vector<analysis::FittedEffect>& effects,
                       const std::string& out_path) {
  write_text_file_atomically(out_path, fixed_model_text(baseline, effects, out_path));
}

}  // namespace shudder::io
