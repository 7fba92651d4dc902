#pragma once
// Which channels and detector settings judge a recording for shudder or judder — one definition
// for the run that writes the verdict and for every later look at its file (plots, reports), so
// the two never disagree:
//   driveline (coupling_torque_Nm recorded): the Haldex coupling's torque and slip, clamp force
//     as the normal force, searched from 2 Hz — the car's shuffle and take-up modes lie at a few
//     to 20 Hz (docs/driveline.md), below the rig's default lower bound;
//   rig (slip_rpm recorded): the torque cell and the clutch slip;
//   prescribed slip: torque_Nm and speed_rpm (the imposed speed is the slip).
// A driveline's oscillation counts only if it repeats and lasts, by the same rule as a network
// clutch's (keep_if_repeated below). A ringing that dies out is the car answering the manoeuvre
// (a torque step rings the shuffle mode), not judder.
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

/// Cycles of the judged frequency a verdict's oscillation must repeat over (keep_if_repeated),
/// and of the lowest searched frequency a network clutch's loaded window must hold.
inline constexpr double kMinJudgedCycles = 3.0;

struct RecordingDetection {
  std::string_view torque_signal;  // the judged torque channel (its spectrum is the one to show)
  std::string_view slip_signal;    // the judged slip channel
  analysis::DetectionInput input;
  analysis::DetectionSettings settings;
  bool sustained_only = false;  // keep_if_repeated applies (drivelines; network clutches call it)
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
/// The sustained-oscillation rule, one for drivelines and network clutches
/// (studies/transient_oscillation.hpp's measures): a stick-slip verdict stands with at least two
/// stick onsets when the contact's stuck flags are recorded; a vibration (or a stick-slip without
/// stuck flags) stands when its swings pass half the threshold 2 kMinJudgedCycles times and its
/// envelope holds: the per-period amplitudes fall from the largest period to the mean of the last
/// two by less per period than a mode of damping ratio 0.005 would, exp(-2 pi 0.005) = 3.1 %
/// per period (a largest period among the last two: holding or growing). Why 0.005 (an
/// estimate): a self-excited oscillation's envelope holds or grows (decay 0); the least-damped
/// passive mode of the shipped models, the rig's torsion bar at 1 % of critical, decays 6.1 %
/// per period, and a drivetrain's shuffle several times that; half the bar's damping lies
/// between with a factor two each side. The rule judges the decay, not the record's length: a
/// ringing still alive when the record ends is no verdict if its envelope falls.
/// Otherwise `r` reads none: frequency, onset, growth and operating point NaN, amplitude and peak
/// frequency kept (what rang).
void keep_if_repeated(const RecordingDetection& detection, analysis::ShudderResult& r);

/// The verdict on a detection case (sustained-oscillation rule included: an oscillation it
/// discards reads as none, its frequency, onset, growth and operating point NaN, its
/// amplitude and peak frequency kept). Throws
/// std::invalid_argument like analysis::detect_shudder (e.g. fewer than 64 samples).
analysis::ShudderResult judge_recording(const RecordingDetection& detection);

}  // namespace shudder::studies
