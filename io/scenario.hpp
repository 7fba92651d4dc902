#pragma once
// Scenario files (TOML) -> validated plain structs in SI units. The schema, with every key,
// unit, default and allowed range, is documented in docs/scenario_format.md. Loading is strict:
// missing required keys, unknown keys, wrong types, non-finite numbers and out-of-range values
// are io::InputError naming the file, line, key and what is allowed.

#include <string>
#include <vector>

#include "clutch/fluid.hpp"
#include "clutch/wet_clutch.hpp"
#include "rig_models/drive_cycle.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::io {

struct Scenario {
  std::string path;         // as given
  std::string text;         // the file's text (stored in outputs)
  std::string name;
  std::string type;         // "prescribed_slip", "rig" or "driveline"
  std::string description;
  std::string fluid_path;   // resolved relative to the scenario file
  clutch::Fluid fluid;
  clutch::WetClutchParams clutch;
  rig_models::DriveCycle cycle;
  rig_models::PrescribedSlipSettings settings;  // duration, steps, sampling, bearing drag
  rig_models::RigParams rig;                    // type "rig" only
  rig_models::DrivelineParams driveline;        // type "driveline" only
  rig_models::DrivelineInputs manoeuvre;        // type "driveline" only
  std::vector<std::string> enabled_effects;  // registry names (rig_models/effect_registry.hpp)
  std::vector<std::string> warnings;         // accepted but worth telling the user

  /// Builds the clutch; throws InputError if the parameters are inconsistent.
  clutch::WetClutch make_clutch() const;
  rig_models::RigSettings rig_settings() const;
  rig_models::DrivelineSettings driveline_settings() const;
};

Scenario load_scenario(const std::string& path);
/// Loads scenario text; `path` names it in messages and anchors relative fluid paths.
Scenario load_scenario_text(const std::string& text, const std::string& path);
/// The scenario text with numeric `key` (dotted, tables created as needed) set to `value`
/// (comments are not kept). Used by sweeps.
std::string set_scenario_key(const std::string& text, const std::string& path,
                             const std::string& key, double value);

}  // namespace shudder::io
