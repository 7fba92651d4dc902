#pragma once
// The channels a network run records (docs/formats/network_file.md "Output"), named after the
// components: `time_s`; NODE.speed_rpm; VEHICLE.speed_km_h; SHAFT.torque_Nm; per clutch
// CLUTCH.torque_Nm, .slip_rpm, .stuck, .normal_force_N, .friction_coefficient (|T| / (R F)) and,
// wet, .interface_mean_temp_C, .interface_max_temp_C, .temp_C (interpolated across thermal steps);
// FREEWHEEL.torque_Nm, .locked; SOURCE.torque_Nm (torque sources, engines, grades, motors);
// TYRE.force_N. Declared once, in that order, for components/channel_recorder.hpp.

#include <deque>
#include <string>
#include <vector>

#include "components/network_builder.hpp"
#include "components/channel_recorder.hpp"

namespace shudder::components {

/// The slow state a network's thermal channels read: every wet clutch's thermal state, in order.
using NetworkSlow = const std::vector<clutch::ThermalState>*;
using NetworkRecorder = components::ChannelRecorder<dynamics::Sample, NetworkSlow>;
using NetworkChannel = NetworkRecorder::Channel;

/// The channels of `built`; `wet_index[c]` is clutch c's index among the thermal states (-1: plain).
/// The channel names live in `names`, which must outlive the recorder's construction.
std::vector<NetworkChannel> network_channels(const NetworkSpec& spec, const BuiltNetwork& built,
                                             const std::vector<int>& wet_index, std::deque<std::string>& names);

}  // namespace shudder::components
