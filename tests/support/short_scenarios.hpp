#pragma once
// Shipped scenarios shortened for end-to-end tests of plots and report directories, their fluid
// paths made absolute so a copy runs from a scratch directory.
#include <string>

#include "tests/support/cli.hpp"

namespace shudder::test {

// The negative-slope rig case shortened to 0.8 s: the clutch-side mode grows at ~13 1/s from
// the start (seeded by the motor ripple and the warming), saturating by ~0.6 s: enough for the
// detector to call it a vibration.
inline std::string short_rig_scenario() {
  std::string s = slurp(source_path("scenarios/rig_shudder_negative_slope.toml"));
  s = replace(s, "duration_s = 2.0", "duration_s = 0.8");
  s = replace(s, "time_s = [0.0, 2.0]", "time_s = [0.0, 0.8]");
  return replace(s, "fluids/schematic_negative_slope.toml",
                 source_path("scenarios/fluids/schematic_negative_slope.toml"));
}

// Paper G Case 1 (prescribed slip) shortened to 3 s.
inline std::string short_prescribed_scenario() {
  std::string s = slurp(source_path("scenarios/paper_g_case1_10kN.toml"));
  s = replace(s, "duration_s = 10.0", "duration_s = 3.0");
  s = replace(s, "time_s = [0.0, 10.0]", "time_s = [0.0, 3.0]");
  s = replace(s, "snapshot_times_s = [3.0, 6.0, 9.0]", "snapshot_times_s = [1.0]");
  return replace(s, "fluids/lsc_fluid_c.toml", source_path("scenarios/fluids/lsc_fluid_c.toml"));
}

}  // namespace shudder::test
