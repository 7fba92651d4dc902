#include "io/fixed_model.hpp"

#include <filesystem>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/toml_reader.hpp"

namespace shudder::io {

namespace fs = std::filesystem;

std::string fixed_model_text(const Scenario& baseline, const std::vector<analysis::FittedEffect>& effects,
                             const std::string& out_path) {
  toml::table doc = TomlTable::parse_text(baseline.text, baseline.path);
  if (auto* clutch = doc["clutch"].as_table(); clutch && clutch->contains("fluid") && !baseline.fluid_path.empty()) {
    const fs::path out_dir = fs::absolute(fs::path(out_path)).parent_path();
    clutch->insert_or_assign("fluid", fs::relative(fs::absolute(baseline.fluid_path), out_dir).generic_string());
  }
  if (!effects.empty() && !doc.contains("effects")) doc.insert("effects", toml::table{});
  auto* tables = doc["effects"].as_table();
  for (const auto& e : effects) {
    if (!tables->contains(e.effect)) tables->insert(e.effect, toml::table{});
    auto* t = (*tables)[e.effect].as_table();
    t->insert_or_assign("enabled", true);
    for (const auto& [key, value] : e.parameters) t->insert_or_assign(key, value);
  }
  std::ostringstream os;
  os << "# Written by `shudder diagnose --write-model`: " << baseline.path << " with the effects it named\n"
     << "# switched on at their fitted parameters.\n"
     << doc << "\n";
  return os.str();
}

void write_fixed_model(const Scenario& baseline, const std::vector<analysis::FittedEffect>& effects,
                       const std::string& out_path) {
  write_text_file_atomically(out_path, fixed_model_text(baseline, effects, out_path));
}

}  // namespace shudder::io
