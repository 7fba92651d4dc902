#pragma once
// What `shudder import` maps a logger's columns to, and in which units: the measured run's
// columns (io/measured_run.hpp) with the units each may be logged in, the `--map
// SOURCE=TARGET:UNIT` option, the mapping file (TOML) a rig's logger keeps, and the automatic
// mapping of names such as `force_kN` or `time [ms]`. docs/formats/import_mapping.md.

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shudder::io {

/// A logged unit of one quantity: value_in_target = scale * logged + offset.
struct ImportUnit {
  std::string name;  // as printed: "ms", "kN", "rad/s", "K", ...
  double scale = 1.0;
  double offset = 0.0;
};

/// One measured-run column an import can write, with the units it may be logged in (the first
/// is the column's own unit).
struct ImportTarget {
  std::string column;    // "normal_force_N"
  std::string quantity;  // "normal force"
  bool required = false;
  std::vector<ImportUnit> units;
};

/// time_s, speed_rpm, normal_force_N, torque_Nm, temp_C (required), sump_temp_C, ir_temp_C.
const std::vector<ImportTarget>& import_targets();
const ImportTarget* find_import_target(const std::string& column);
/// The unit of `target` called `unit` (spaces, '_', '*', middle dots and '/' ignored, "°C",
/// "degC" and "C" alike); nullptr if `target` cannot be logged in it.
const ImportUnit* find_import_unit(const ImportTarget& target, const std::string& unit);
/// "s, ms" for messages.
std::string unit_list(const ImportTarget& target);

/// One logger column mapped to one measured-run column.
struct ColumnMapping {
  std::string source;  // logger column name
  std::string target;  // measured-run column
  std::string unit;    // the unit as given (find_import_unit resolves it)
  std::string origin;  // where it came from, for messages: "--map ...", "map.toml:4", "automatic"
};

/// What an import is told: mappings, metadata and the CSV's dialect.
struct ImportSpec {
  std::vector<ColumnMapping> maps;                            // explicit ones, in order
  std::vector<std::pair<std::string, std::string>> metadata;  // written as given
  char delimiter = 0;                                         // 0 = detect
  char decimal = 0;                                           // 0 = detect
  bool trust_units = false;                                   // skip the plausibility checks
  bool from_mapping_file = false;                             // read_import_mapping filled it
};

/// The spec of `--map` options and a `--mapping` file (empty: none), as every command takes them.
ImportSpec import_spec_of(const std::vector<std::string>& maps, const std::string& mapping_file);

/// `--map SOURCE=TARGET:UNIT` (UNIT optional: the target's own unit). InputError naming the
/// option on a malformed spec, an unknown target or a unit the target cannot be logged in.
ColumnMapping parse_map_option(const std::string& spec);
/// The `--map SOURCE=TARGET:UNIT` option a message suggests, single-quoted for the shell when
/// the logger's column name holds anything but letters, digits and `_.-` ("Zeit [ms]").
std::string map_option_text(const std::string& source, const std::string& target, const std::string& unit);
/// `--meta KEY=VALUE`.
std::pair<std::string, std::string> parse_meta_option(const std::string& spec);
/// "," ";" "tab" "auto" (0) for --delimiter; "." "," "auto" (0) for --decimal.
char parse_delimiter(const std::string& text, const std::string& where);
char parse_decimal(const std::string& text, const std::string& where);

/// Reads a mapping file into `spec` (its maps first, then those already in `spec` override
/// them; its metadata only where `spec` has none under that key; its dialect unless set).
/// Strict: unknown keys, bad units and unknown targets are InputErrors with the file's line.
void read_import_mapping(const std::string& path, ImportSpec& spec);

/// The automatic mapping of a logger column name: `force_kN` -> normal_force_N in kN,
/// `time [ms]` -> time_s in ms, `temp_C` -> temp_C. nullopt when the name is not recognised;
/// `unit` is empty when the quantity is recognised but the name carries no unit.
std::optional<ColumnMapping> automatic_mapping(const std::string& name);

}  // namespace shudder::io
