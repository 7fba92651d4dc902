#pragma once
// The verdict block every run stores (/analysis/verdict in its HDF5, verdict.json in its
// report, the verdict lines of its summary): what the recording shows and what linear theory
// predicted at the same operating point, side by side.
//
//   judged     the recording judged once, by studies/recording_detection (the channels, band
//              and the driveline's sustained-oscillation rule every reader uses): verdict none /
//              vibration / stick_slip, dominant frequency f_d (Hz), amplitude A (half
//              peak-to-peak of the torque about its one-period moving mean, N m), onset time (s)
//              — analysis/shudder_detection.hpp, definitions 1–8.
//   window     the judged window the operating point is averaged over: the oscillating part
//              [oscillating_from_s, oscillating_to_s] (definition 4) when there is an
//              oscillation — the sliding state that shudders; the whole record when there is
//              none. Over it, the means of the judged slip (rpm, signed), the mean interface
//              temperature (°C) and the normal force (N; the driveline: the coupling's clamp
//              force). A mean over an oscillation is the steady sliding it oscillates about
//              (the housing's mean speed on its bar is zero, so the mean slip is the drive's).
//   predicted  the kind's linear stability at that operating point, where the kind has one:
//              margin = largest real part of the linearised system's eigenvalues (1/s; > 0
//              unstable, <= 0 stable: analysis/stability.hpp's convention), the oscillatory
//              mode's margin and frequency (the clutch-side mode a shudder would have). The
//              rig: studies/rig_stability.hpp with the isothermal friction slope and every
//              ring at the window's mean interface temperature. Kinds without a predictor say
//              "not predicted" and why; nothing is invented.
// A verdict block holds the judged and predicted values even when they disagree: that
// disagreement (e.g. a stable prediction with a simulated shudder) is for the reader to see.

#include <limits>
#include <string>

#include "analysis/shudder_detection.hpp"
#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "studies/recording_detection.hpp"

namespace shudder::studies {

/// Name of the block in Recording::blocks and of its group under /analysis.
inline constexpr const char* kVerdictBlock = "verdict";

/// Linear theory at the run's operating point, or the reason there is none.
struct Prediction {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  bool made = false;
  std::string method;                      // how it was predicted, or "not predicted: <why>"
  double margin_per_s = kNaN;              // largest real part, 1/s; > 0 unstable
  double oscillatory_margin_per_s = kNaN;  // largest real part of an oscillatory mode, 1/s
  double frequency_Hz = kNaN;              // that oscillatory mode's frequency, Hz

  /// "not predicted: <why>".
  static Prediction none(const std::string& why);
};

/// The means over the judged window (see the header comment).
struct OperatingWindow {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string what;  // "oscillating part" or "whole run"
  double from_s = kNaN, to_s = kNaN;
  double slip_rpm = kNaN;          // signed mean of the judged slip
  double interface_temp_C = kNaN;  // NaN if not recorded
  double normal_force_N = kNaN;    // NaN if not recorded
};

struct RunVerdict {
  std::string torque_signal, slip_signal;  // the judged channels
  analysis::ShudderResult judged;
  OperatingWindow window;
  Prediction prediction;
};

/// Judges `rec` and averages its operating point over the judged window. Throws
/// std::invalid_argument if the recording cannot be judged (no time, torque or slip channel;
/// fewer than 64 samples; non-uniform sampling), with the reason.
RunVerdict judge_run(const dynamics::Recording& rec);
/// The same for a detection case assembled by the caller (a network's clutch: its own channels
/// and settings, studies/network_run.hpp).
RunVerdict judge_detection(const RecordingDetection& detection);

/// The rig's linear stability at `window` (rig_stability.hpp at the window's mean force, slip
/// and interface temperature); Prediction::none with the reason where it cannot be made (no
/// force, an unrecorded temperature, a motor that cannot hold the slip).
Prediction predict_rig(const rig_models::RigParams& params, const clutch::WetClutch& clutch,
                       const OperatingWindow& window);

/// The block stored with the run (docs/formats/run_output.md "The verdict block"): texts `verdict`,
/// `judged_signals`, `operating_window`, `prediction`; scalars verdict_code, frequency_Hz,
/// peak_frequency_Hz, amplitude_Nm, threshold_Nm, onset_time_s, window_from_s, window_to_s, slip_rpm,
/// interface_temp_C, normal_force_N, predicted_margin_per_s, predicted_oscillatory_margin_per_s,
/// predicted_frequency_Hz (NaN where undefined: no oscillation, not predicted, not recorded).
dynamics::ResultBlock verdict_block(const RunVerdict& verdict);

/// The block of a recording judge_run refused: texts `verdict` = "not_judged" and `reason`
/// (`why`), no values.
dynamics::ResultBlock not_judged_block(const std::string& why);

}  // namespace shudder::studies
