// Import targets, units and mappings (see import_mapping.hpp).
#include "io/import_mapping.hpp"

#include <algorithm>
#include <cctype>
#include <numbers>
#include <sstream>

#include "core/nearest_name.hpp"
#include "io/input_error.hpp"
#include "io/toml_reader.hpp"

namespace shudder::io {

namespace import_mapping_impl {

// A unit's spelling reduced to compare: no spaces, '_', '*', '/', '.', middle dot or degree sign.
std::string unit_key(const std::string& unit) {
  std::string out;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(unit[i]);
    if (c == ' ' || c == '_' || c == '*' || c == '/' || c == '.' || c == '-') continue;
    if (unit.compare(i, 2, "\xC2\xB7") == 0 || unit.compare(i, 2, "\xC2\xB0") == 0) {  // · and °
      ++i;
      continue;
    }
    out += static_cast<char>(c);
  }
  if (out == "degC" || out == "deg" || out == "Celsius") return "C";
  if (out == "RPM" || out == "1min") return "rpm";
  return out;
}

std::string target_list() {
  std::string out;
  for (const auto& t : import_targets()) out += (out.empty() ? "" : ", ") + t.column;
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Logger names for each target (lower case, '_' between words), the measured run's own first.
struct Alias {
  const char* column;
  std::vector<std::string> names;
};
const std::vector<Alias>& aliases() {
  static const std::vector<Alias> a = {
      {"time_s", {"time", "t", "timestamp", "zeit"}},
      {"speed_rpm", {"speed", "slip", "slip_speed", "sliding_speed", "omega", "angular_speed", "n", "rpm"}},
      {"normal_force_N", {"normal_force", "force", "load", "clamp_force", "axial_force", "f_n", "fn"}},
      {"torque_Nm", {"torque", "friction_torque", "m", "tq"}},
      {"temp_C", {"temp", "temperature", "disc_temp", "separator_temp", "thermocouple", "tc"}},
      {"sump_temp_C", {"sump_temp", "oil_temp", "sump_temperature", "oil_temperature"}},
      {"ir_temp_C", {"ir_temp", "ir_temperature", "pyrometer"}},
  };
  return a;
}

// Unit suffixes of logger names ("force_kN"): the spelling after the last '_' and the unit.
const std::vector<std::pair<std::string, std::string>>& unit_suffixes() {
  static const std::vector<std::pair<std::string, std::string>> s = {
      {"ms", "ms"},   {"s", "s"},    {"rpm", "rpm"},   {"RPM", "rpm"},  {"rad_s", "rad/s"}, {"rads", "rad/s"},
      {"kN", "kN"},   {"KN", "kN"},  {"N", "N"},       {"kNm", "kN m"}, {"kN_m", "kN m"},   {"Nm", "N m"},
      {"N_m", "N m"}, {"C", "degC"}, {"degC", "degC"}, {"K", "K"}};
  return s;
}

}  // namespace import_mapping_impl

const std::vector<ImportTarget>& import_targets() {
  static const std::vector<ImportTarget> targets = [] {
    const double rad_s_to_rpm = 60.0 / (2.0 * std::numbers::pi);
    const std::vector<ImportUnit> temp = {{"degC", 1.0, 0.0}, {"K", 1.0, -273.15}};
    return std::vector<ImportTarget>{
        {"time_s", "time", true, {{"s", 1.0, 0.0}, {"ms", 1e-3, 0.0}}},
        {"speed_rpm", "sliding speed", true, {{"rpm", 1.0, 0.0}, {"rad/s", rad_s_to_rpm, 0.0}}},
        {"normal_force_N", "normal force", true, {{"N", 1.0, 0.0}, {"kN", 1e3, 0.0}}},
        {"torque_Nm", "torque", true, {{"N m", 1.0, 0.0}, {"kN m", 1e3, 0.0}}},
        {"temp_C", "disc temperature", true, temp},
        {"sump_temp_C", "sump temperature", false, temp},
        {"ir_temp_C", "IR temperature", false, temp},
    };
  }();
  return targets;
}

const ImportTarget* find_import_target(const std::string& column) {
  for (const auto& t : import_targets())
    if (t.column == column) return &t;
  return nullptr;
}

const ImportUnit* find_import_unit(const ImportTarget& target, const std::string& unit) {
  using import_mapping_impl::unit_key;
  const std::string key = unit_key(unit);
  for (const auto& u : target.units)
    if (unit_key(u.name) == key) return &u;
  return nullptr;
}

std::string unit_list(const ImportTarget& target) {
  std::string out;
  for (const auto& u : target.units) out += (out.empty() ? "" : ", ") + u.name;
  return out;
}

namespace import_mapping_impl {

// Checks target and unit of `m`; `where`/`line` name the place in errors.
void check_mapping(const ColumnMapping& m, const std::string& where, long line, const std::string& key) {
  const ImportTarget* target = find_import_target(m.target);
  if (!target) {
    std::vector<std::string> names;
    for (const auto& t : import_targets()) names.push_back(t.column);
    const std::string near = nearest_key(m.target, names);
    throw InputError(where, line, key,
                     "'" + m.target + "' is not a measured-run column" +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)") + "; allowed: " + target_list());
  }
  if (!m.unit.empty() && !find_import_unit(*target, m.unit))
    throw InputError(
        where, line, key,
        "unit '" + m.unit + "' is not one " + m.target + " can be logged in; allowed: " + unit_list(*target));
}

// "TARGET:UNIT" or "TARGET" into `m`.
void split_target(const std::string& text, ColumnMapping& m) {
  const auto colon = text.find(':');
  m.target = text.substr(0, colon);
  m.unit = colon == std::string::npos ? "" : text.substr(colon + 1);
}

}  // namespace import_mapping_impl

std::string map_option_text(const std::string& source, const std::string& target, const std::string& unit) {
  const std::string spec = source + "=" + target + ":" + unit;
  const bool plain = std::all_of(source.begin(), source.end(),
                                 [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '.' || c == '-'; });
  if (plain) return "--map " + spec;
  std::string quoted = "'";
  for (const char c : spec) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return "--map " + quoted + "'";
}

ColumnMapping parse_map_option(const std::string& spec) {
  using namespace import_mapping_impl;
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
    throw InputError("--map", 0, "",
                     "'" + spec +
                         "' is not SOURCE=TARGET:UNIT; e.g. --map force_kN=normal_force_N:kN (the unit may be "
                         "left out when the column is in the target's own unit)");
  ColumnMapping m;
  m.source = spec.substr(0, eq);
  split_target(spec.substr(eq + 1), m);
  m.origin = "--map " + spec;
  check_mapping(m, "--map " + spec, 0, "");
  return m;
}

std::pair<std::string, std::string> parse_meta_option(const std::string& spec) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--meta", 0, "", "'" + spec + "' is not KEY=VALUE; e.g. --meta oil_flow_ml_min=200");
  std::string key = spec.substr(0, eq);
  if (key == "format") throw InputError("--meta", 0, "", "'format' is written by the import itself; give other keys");
  return {key, spec.substr(eq + 1)};
}

char parse_delimiter(const std::string& text, const std::string& where) {
  if (text == "auto") return 0;
  if (text == "," || text == "comma") return ',';
  if (text == ";" || text == "semicolon") return ';';
  if (text == "tab" || text == "\t") return '\t';
  throw InputError(where, 0, "", "'" + text + "' is not a delimiter; allowed: auto, ',', ';', tab");
}

char parse_decimal(const std::string& text, const std::string& where) {
  if (text == "auto") return 0;
  if (text == "." || text == "point") return '.';
  if (text == "," || text == "comma") return ',';
  throw InputError(where, 0, "", "'" + text + "' is not a decimal separator; allowed: auto, '.', ','");
}

ImportSpec import_spec_of(const std::vector<std::string>& maps, const std::string& mapping_file) {
  ImportSpec spec;
  for (const auto& m : maps) spec.maps.push_back(parse_map_option(m));
  if (!mapping_file.empty()) read_import_mapping(mapping_file, spec);
  return spec;
}

void read_import_mapping(const std::string& path, ImportSpec& spec) {
  using namespace import_mapping_impl;
  spec.from_mapping_file = true;
  const toml::table root = TomlTable::parse_file(path);
  TomlTable top(root, path, "");
  const auto line_of = [](const toml::node& n) { return static_cast<long>(n.source().begin.line); };
  const std::string delimiter = top.string_or("delimiter", "auto");
  const std::string decimal = top.string_or("decimal", "auto");
  try {
    if (!spec.delimiter) spec.delimiter = parse_delimiter(delimiter, path);
    if (!spec.decimal) spec.decimal = parse_decimal(decimal, path);
  } catch (const InputError& e) {
    top.fail(delimiter != "auto" && !spec.delimiter ? "delimiter" : "decimal", e.what());
  }
  if (top.has("trust_units")) spec.trust_units = top.boolean("trust_units") || spec.trust_units;

  std::vector<ColumnMapping> maps;
  if (const auto* columns = root.get("columns")) {
    top.mark_read("columns");
    const auto* table = columns->as_table();
    if (!table) throw InputError(path, line_of(*columns), "columns", "must be a table of SOURCE = \"TARGET:UNIT\"");
    for (const auto& [key, value] : *table) {
      const std::string source(key.str());
      const auto* text = value.as_string();
      if (!text)
        throw InputError(path, line_of(value), "columns." + source,
                         "must be a string \"TARGET:UNIT\", e.g. \"normal_force_N:kN\"");
      ColumnMapping m;
      m.source = source;
      split_target(text->get(), m);
      m.origin = path + ":" + std::to_string(line_of(value));
      check_mapping(m, path, line_of(value), "columns." + source);
      maps.push_back(std::move(m));
    }
  }
  if (const auto* metadata = root.get("metadata")) {
    top.mark_read("metadata");
    const auto* table = metadata->as_table();
    if (!table) throw InputError(path, line_of(*metadata), "metadata", "must be a table of KEY = value");
    for (const auto& [key, value] : *table) {
      const std::string k(key.str());
      std::string v;
      if (const auto* s = value.as_string()) {
        v = s->get();
      } else if (value.is_number()) {
        std::ostringstream os;
        os << value.value<double>().value_or(0.0);
        v = os.str();
      } else {
        throw InputError(path, line_of(value), "metadata." + k, "must be a string or a number");
      }
      if (k == "format") throw InputError(path, line_of(value), "metadata.format", "is written by the import itself");
      const bool given =
          std::any_of(spec.metadata.begin(), spec.metadata.end(), [&](const auto& kv) { return kv.first == k; });
      if (!given) spec.metadata.emplace_back(k, v);
    }
  }
  top.finish();
  // The command line's maps win over the file's for the same source column.
  for (const auto& m : spec.maps)
    maps.erase(std::remove_if(maps.begin(), maps.end(), [&](const ColumnMapping& f) { return f.source == m.source; }),
               maps.end());
  maps.insert(maps.end(), spec.maps.begin(), spec.maps.end());
  spec.maps = std::move(maps);
}

std::optional<ColumnMapping> automatic_mapping(const std::string& name) {
  using namespace import_mapping_impl;
  std::string base = name, unit;
  // "time [ms]", "force (kN)", "torque / N m"
  if (const auto open = name.find_first_of("[(");
      open != std::string::npos && open > 0 && (name.back() == ']' || name.back() == ')')) {
    base = name.substr(0, open);
    unit = name.substr(open + 1, name.size() - open - 2);
  } else if (const auto slash = name.find(" / "); slash != std::string::npos) {
    base = name.substr(0, slash);
    unit = name.substr(slash + 3);
  }
  while (!base.empty() && (base.back() == ' ' || base.back() == '_')) base.pop_back();
  std::string key = lower(base);
  std::replace(key.begin(), key.end(), ' ', '_');
  std::replace(key.begin(), key.end(), '-', '_');
  const auto make = [&](const Alias& a, const std::string& u) {
    ColumnMapping m;
    m.source = name;
    m.target = a.column;
    m.unit = u;
    m.origin = "automatic";
    return m;
  };
  if (unit.empty()) {
    // The name itself a measured-run column ("speed_rpm"), an alias with a unit suffix
    // ("force_kN", "speed_rad_s"), or an alias alone (no unit known).
    for (const auto& a : aliases())
      if (name == a.column) return make(a, find_import_target(a.column)->units.front().name);
    for (const auto& a : aliases())
      for (const auto& [spelled, unit_name] : unit_suffixes()) {
        if (!find_import_unit(*find_import_target(a.column), unit_name)) continue;
        const std::string suffix = "_" + spelled;
        if (name.size() <= suffix.size() || !name.ends_with(suffix)) continue;
        const std::string prefix = lower(name.substr(0, name.size() - suffix.size()));
        for (const auto& alias : a.names)
          if (prefix == alias) return make(a, unit_name);
      }
    for (const auto& a : aliases())
      for (const auto& alias : a.names)
        if (key == alias) return make(a, "");
    return std::nullopt;
  }
  for (const auto& a : aliases())
    for (const auto& alias : a.names)
      if (key == alias) {
        const ImportTarget& t = *find_import_target(a.column);
        const ImportUnit* u = find_import_unit(t, unit);
        return make(a, u ? u->name : unit);  // a unit it cannot be logged in: checked by the import
      }
  return std::nullopt;
}

}  // namespace shudder::io
