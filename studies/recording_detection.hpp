#pragma once
// Which channels and detector settings judge a recording for shudder or judder — one definition
// for the run that writes the verdict and for every later look at its file (plots, reports), so
// the two never disagree:
//   driveline (coupling_torque_Nm recorded): the Haldex coupling's torque and slip, clamp force
//     as the normal force, searched from 2 Hz — the car's shuffle and take-up modes lie at a few
//     to 20 Hz (docs/driveline.md), below the rig's default lower bound;
//   rig (slip_rpm recorded): the torque cell and the clutch slip;
//   prescribed slip: torque_Nm and speed_rpm (the imposed speed is the slip).
// A driveline's oscillation counts only if it is sustained: it must keep half its amplitude over
// the record's last two periods (or last tenth, if longer). A ringing that dies out is the car
// answering the manoeuvre (a torque step rings the shuffle mode), not judder.
// Stuck flags, interface temperature and normal force are used when recorded.
// The onset reported is the detector's threshold-crossing onset (analysis/shudder_detection.hpp):
// the time the oscillation's amplitude last rose through the verdict's threshold, independent of the start
// transient and of the thermal step (docs/rig_model.md).

#include <optional>
#include <string>
#include <string_view>

#include "analysis/shudder_detection.hpp"
#include "dynamics/recording.hpp"

namespace shudder::studies {

struct RecordingDetection {
  std::string_view torque_signal;  // the judged torque channel (its spectrum is the one to show)
  std::string_view slip_signal;    // the judged slip channel
  analysis::DetectionInput input;
  analysis::DetectionSettings settings;
  bool sustained_only = false;  // a decaying oscillation is no verdict (drivelines)
};

/// A network run's judged clutch (the `clutch` text of its verdict block, studies/network_run.hpp).
/// its channels CLUTCH.torque_Nm and CLUTCH.slip_rpm stand for torque_Nm and slip_rpm in plots
/// of the file. nullptr for the other kinds' recordings.
const std::string* network_verdict_clutch(const dynamics::Recording& rec);
/// The torque channel a recording is judged on: coupling_torque_Nm for a driveline, the judged
/// clutch's torque for a network, else torque_Nm.
std::string_view judged_torque_signal(const dynamics::Recording& rec);
/// The detection case of a recording; nullopt when it lacks time, torque or slip.
std::optional<RecordingDetection> recording_detection(const dynamics::Recording& rec);
/// The verdict on a detection case (sustained-oscillation rule included: an oscillation it
/// discards reads as none, its frequency, onset, growth and operating point NaN, its
/// amplitude and peak frequency kept). Throws
/// std::invalid_argument like analysis::detect_shudder (e.g. fewer than 64 samples).
analysis::ShudderResult judge_recording(const RecordingDetection& detection);

}  // namespace shudder::studies
