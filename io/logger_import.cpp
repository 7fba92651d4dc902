// Logger CSV -> measured run (see logger_import.hpp).
#include "io/logger_import.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/nearest_name.hpp"
#include "io/import_plausibility.hpp"
#include "io/input_error.hpp"
#include "io/logger_csv.hpp"

namespace shudder::io {

const std::vector<std::pair<std::string, std::string>>& import_metadata_defaults() {
  static const std::vector<std::pair<std::string, std::string>> d = {
      {"rig", "lsctr"},
      {"temp_sensor", "separator_thermocouple r_mm=48 z_mm=0.5"},
      {"oil_flow_ml_min", "200"},
  };
  return d;
}

namespace logger_import_impl {

std::string quoted_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out;
}

// The explicit maps, then the automatic ones for the columns and targets they leave.
std::vector<ColumnMapping> resolve(const LoggerTable& t, const ImportSpec& spec) {
  std::vector<ColumnMapping> maps;
  for (const auto& m : spec.maps) {
    if (std::find(t.names.begin(), t.names.end(), m.source) == t.names.end()) {
      const std::string near = nearest_key(m.source, t.names);
      throw InputError(m.origin, 0, "",
                       "the logger file " + t.path + " has no column '" + m.source + "'" +
                           (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                           "; its columns: " + quoted_names(t.names));
    }
    for (const auto& other : maps)
      if (other.target == m.target)
        throw InputError(m.origin, 0, "",
                         "'" + other.source + "' (" + other.origin + ") is already mapped to " + m.target +
                             "; map one column to each measured-run column");
    maps.push_back(m);
  }
  // Automatic candidates per target; a name that gives its unit wins over one that does not
  // (a stray column "n" does not compete with "speed_rpm"); two with units are ambiguous.
  std::vector<ColumnMapping> automatic;
  for (const auto& target : import_targets()) {
    if (std::any_of(maps.begin(), maps.end(), [&](const auto& e) { return e.target == target.column; })) continue;
    std::vector<ColumnMapping> with_unit, without_unit;
    for (const auto& name : t.names) {
      if (std::any_of(maps.begin(), maps.end(), [&](const auto& m) { return m.source == name; })) continue;
      const auto m = automatic_mapping(name);
      if (!m || m->target != target.column) continue;
      (m->unit.empty() ? without_unit : with_unit).push_back(*m);
    }
    if (with_unit.size() > 1)
      throw InputError(t.path, 0, "",
                       "columns '" + with_unit[0].source + "' and '" + with_unit[1].source + "' both look like " +
                           target.column + "; choose one with --map COLUMN=" + target.column + ":UNIT");
    if (with_unit.empty() && !without_unit.empty() && target.required)
      throw InputError(t.path, 0, "",
                       "column '" + without_unit.front().source + "' looks like " + target.column + " (" +
                           target.quantity + ") but its name gives no unit; give " +
                           map_option_text(without_unit.front().source, target.column, "UNIT") +
                           " (allowed units: " + unit_list(target) + ")");
    if (with_unit.empty()) continue;
    const ColumnMapping& m = with_unit.front();
    if (!find_import_unit(target, m.unit))
      throw InputError(t.path, 0, "",
                       "column '" + m.source + "' looks like " + m.target + " in '" + m.unit +
                           "', which is not a unit it can be logged in; allowed: " + unit_list(target) + " (give " +
                           map_option_text(m.source, m.target, "UNIT") + ")");
    automatic.push_back(m);
  }
  maps.insert(maps.end(), automatic.begin(), automatic.end());
  for (const auto& target : import_targets())
    if (target.required &&
        std::none_of(maps.begin(), maps.end(), [&](const auto& m) { return m.target == target.column; }))
      throw InputError(t.path, 0, "",
                       "no column for " + target.column + " (" + target.quantity +
                           "); the file's columns: " + quoted_names(t.names) + "; give --map COLUMN=" + target.column +
                           ":UNIT (units: " + unit_list(target) + ") or a mapping file (--mapping)");
  return maps;
}

std::string g6(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace logger_import_impl

MeasuredRun read_measured_or_logger(const std::string& path, const ImportSpec& spec,
                                    std::vector<std::string>& warnings) {
  if (spec.maps.empty() && !spec.from_mapping_file) return read_measured_run(path);
  ImportResult r = import_logger(path, spec);
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  return std::move(r.run);
}

ImportResult import_logger(const std::string& logger_path, const ImportSpec& spec) {
  using namespace logger_import_impl;
  LoggerCsvOptions csv;
  csv.delimiter = spec.delimiter;
  csv.decimal = spec.decimal;
  const LoggerTable t = read_logger_csv(logger_path, csv);
  ImportResult result;
  result.delimiter = t.delimiter;
  result.decimal = t.decimal;
  if (t.row_lines.size() < measured_run_min_rows)
    throw InputError(logger_path, 0, "",
                     "only " + std::to_string(t.row_lines.size()) + " data row(s); a measured run needs at least " +
                         std::to_string(measured_run_min_rows));

  const std::vector<ColumnMapping> maps = resolve(t, spec);
  MeasuredRun& run = result.run;
  run.path = logger_path;
  // Columns in the measured run's order: the required ones, then the optional ones mapped.
  for (const auto& target : import_targets()) {
    const auto m = std::find_if(maps.begin(), maps.end(), [&](const auto& x) { return x.target == target.column; });
    if (m == maps.end()) continue;
    const std::size_t source =
        static_cast<std::size_t>(std::find(t.names.begin(), t.names.end(), m->source) - t.names.begin());
    const ImportUnit& unit = m->unit.empty() ? target.units.front() : *find_import_unit(target, m->unit);
    std::vector<double> values = t.columns[source];
    for (double& v : values) v = unit.scale * v + unit.offset;
    if (!spec.trust_units) check_unit_plausible(logger_path, *m, target, unit, values);
    run.columns.push_back({target.column, measured_run_units(target.column), std::move(values)});
    result.mapping.push_back(m->source + " -> " + target.column + " (" + unit.name +
                             (m->origin == "automatic" ? ", from its name)" : ")"));
  }
  for (const auto& name : t.names)
    if (std::none_of(maps.begin(), maps.end(), [&](const auto& m) { return m.source == name; }))
      result.ignored.push_back(name);

  // The measured run's row rules, named by the logger's line.
  const auto& time = *run.column("time_s");
  for (std::size_t r = 1; r < time.size(); ++r)
    if (!(time[r] > time[r - 1]))
      throw InputError(logger_path, t.row_lines[r], "",
                       "time " + g6(time[r]) + " s is not after " + g6(time[r - 1]) + " s on line " +
                           std::to_string(t.row_lines[r - 1]) + "; time must be strictly increasing");
  auto& force = std::find_if(run.columns.begin(), run.columns.end(), [](const auto& c) {
                  return c.name == "normal_force_N";
                })->values;
  const double f_max = *std::max_element(force.begin(), force.end());
  std::size_t clipped = 0;
  for (std::size_t r = 0; r < force.size(); ++r) {
    if (force[r] >= 0.0) continue;
    // A load cell's zero offset or noise at no load: up to 1 % of the largest force (or 100 N).
    if (force[r] < -std::max(100.0, 0.01 * f_max))
      throw InputError(logger_path, t.row_lines[r], "",
                       "normal force " + g6(force[r]) +
                           " N is negative beyond a load cell's offset (1 % of the "
                           "largest force, at least 100 N); a normal force must be >= 0");
    force[r] = 0.0;
    ++clipped;
  }
  if (clipped)
    result.warnings.push_back(logger_path + ": " + std::to_string(clipped) +
                              " slightly negative normal force(s) (load cell offset or noise) written as 0 N");

  // Metadata: format, then the logger's own '# key: value' lines, the given ones over them,
  // then documented defaults for what is still missing.
  run.metadata.emplace_back("format", std::string(measured_run_format));
  const auto set = [&](const std::string& key, const std::string& value) {
    for (auto& kv : run.metadata)
      if (kv.first == key) {
        kv.second = value;
        return;
      }
    run.metadata.emplace_back(key, value);
  };
  for (const auto& [k, v] : t.metadata)
    if (k != "format") set(k, v);
  for (const auto& [k, v] : spec.metadata) set(k, v);
  if (const auto flow = run.meta("oil_flow_ml_min")) {
    char* end = nullptr;
    const double v = std::strtod(flow->c_str(), &end);
    if (end == flow->c_str() || *end != '\0' || !std::isfinite(v) || v < 0)
      throw InputError(logger_path, 0, "oil_flow_ml_min", "'" + *flow + "' is not a flow; give a number >= 0 (ml/min)");
  }
  std::string defaulted;
  for (const auto& [k, v] : import_metadata_defaults())
    if (!run.meta(k)) {
      run.metadata.emplace_back(k, v);
      defaulted += (defaulted.empty() ? "" : ", ") + k + "=" + v;
    }
  if (!defaulted.empty())
    result.warnings.push_back(logger_path + ": metadata not given, written with the defaults " + defaulted +
                              " (give --meta KEY=VALUE or [metadata] in a mapping file; docs/formats/measured_run.md)");
  set("imported_from", std::filesystem::path(logger_path).filename().string());
  return result;
}

}  // namespace shudder::io
