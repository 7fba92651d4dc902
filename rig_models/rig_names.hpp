#pragma once
// The `rig` metadata of measured runs (docs/formats/run_output.md, docs/formats/measured_run.md): which
// machine a run was logged on, so `diagnose` can warn when runs and model do not match.
#include <string_view>

namespace shudder::rig_models {

/// Runs of the Limited Slip Clutch Test Rig (thesis Paper A), and prescribed-slip runs of its clutch.
inline constexpr std::string_view kLsctrRig = "lsctr";
/// Runs of a driveline's Haldex coupling (rig_models/coupling_measurement.hpp).
inline constexpr std::string_view kCouplingRig = "haldex_coupling";
/// Runs of one wet clutch of a network scenario (app/cmd_run_network.cpp: one file per clutch).
inline constexpr std::string_view kNetworkClutchRig = "network_clutch";

}  // namespace shudder::rig_models
