#pragma once
// The `rig` metadata of measured runs (docs/run_output.md, FORMATS.md measured-run files): which
// machine a run was logged on, so `diagnose` can warn when runs and model do not match.
#include <string_view>

namespace shudder::rig_models {

/// Runs of the Limited Slip Clutch Test Rig (thesis Paper A), and prescribed-slip runs of its clutch.
inline constexpr std::string_view kLsctrRig = "lsctr";
/// Runs of a driveline's Haldex coupling (rig_models/coupling_measurement.hpp).
inline constexpr std::string_view kCouplingRig = "haldex_coupling";

}  // namespace shudder::rig_models
