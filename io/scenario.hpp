#pragma once
// Scenario files (TOML) -> validated plain structs in SI units. The schema, with every key,
// unit, default and allowed range, is documented in docs/formats/scenario_file.md. Loading is strict:
// missing required keys, unknown keys, wrong types, non-finite numbers and out-of-range values
// are io::InputError naming the file, line, key and what is allowed.

#include <string>
#include <vector>

#include "clutch/fluid.hpp"
#include "clutch/wet_clutch.hpp"
#include "core/model_kind.hpp"
#include "components/network_spec.hpp"
#include "io/toml_reader.hpp"
#include "rig_models/model.hpp"

namespace shudder::io {

/// A loaded scenario: what every kind shares (the file, the clutch and its fluid, the effects)
/// and the typed model of its kind (rig_models/model.hpp). The file's `type` string is mapped
/// to the kind once, by the loader; everything else dispatches on `model`.
struct Scenario {
  std::string path;  // as given
  std::string text;  // the file's text (stored in outputs)
  std::string name;
  std::string description;
  std::string fluid_path;  // resolved relative to the scenario file
  std::string fluid_text;  // the fluid file's text as read (stored in outputs beside `text`)
  clutch::Fluid fluid;
  clutch::WetClutchParams clutch;  // every kind; clutch effects applied
  rig_models::Model model;         // the kind and what it needs (rig and driveline params,
                                   // drive cycle or manoeuvre, settings); effects applied
  // [effects.stick_time_static_friction] as read. Applied to the rig and driveline models; kept
  // here because a prescribed_slip model has no use for it but the diagnosis must still know
  // whether it is switched on (io/diagnosis_inputs.cpp).
  components::StickTimeFriction stick_time;
  std::vector<std::string> enabled_effects;  // registry names (rig_models/effect_registry.hpp)
  std::vector<std::string> warnings;         // accepted but worth telling the user

  ModelKind kind() const { return rig_models::kind(model); }
  /// Builds the clutch; throws InputError if the parameters are inconsistent.
  clutch::WetClutch make_clutch() const;
};

Scenario load_scenario(const std::string& path);
/// A scenario (or fluid) file's text; InputError naming the file if it cannot be read.
std::string read_scenario_text(const std::string& path);
/// Loads scenario text; `path` names it in messages and anchors relative fluid paths.
Scenario load_scenario_text(const std::string& text, const std::string& path);
/// A network's wet clutch (docs/formats/network_file.md): `component` holds a [clutch] table and an
/// optional [effects] table exactly as a scenario's root does; the fluid path is relative to
/// the scenario file. Effects that cannot act on it are warnings (appended).
components::WetPackSpec read_wet_pack(TomlTable& component, const std::string& scenario_path,
                                      std::vector<std::string>& warnings);

/// The scenario text with numeric `key` (dotted, tables created as needed) set to `value`
/// (comments are not kept); a whole number is written as an integer. Used by sweeps.
std::string set_scenario_key(const std::string& text, const std::string& path, const std::string& key, double value);

}  // namespace shudder::io
