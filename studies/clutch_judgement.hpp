#pragma once
// A network clutch judged for shudder and stick-slip on its own channels (CLUTCH.torque_Nm,
// .slip_rpm, .stuck, .normal_force_N, .interface_mean_temp_C), and the run's verdict: the worst.
//
// Judging a clutch (analysis/shudder_detection.hpp's detector) covers its LOADED WINDOW: from
// its first sample with normal force > 0 to its last sample slipping under load. A launch
// judders while the clutch slips and then locks; the lock-up that ends an engagement, and what
// follows it, is no stick-slip, while sticking again and again inside the window is. The search
// starts at max(2 Hz, 3 / window length): a car's shuffle and take-up modes lie at a few Hz, and
// a frequency counts only if the window holds three of its cycles. A window of fewer than
// kMinJudgedSamples samples is "not judged", with the reason. An oscillation counts only if it
// repeats and lasts to the window's end (studies/recording_detection.hpp's keep_if_repeated, the
// rule a driveline's coupling is judged by): a ringing that dies out while the clutch still
// slips is the drivetrain answering a step; a judder lasts until the clutch locks or opens.
// The run's verdict is the worst clutch's: stick_slip over vibration over none; between equals,
// the larger amplitude. Blocks: `verdict.CLUTCH` per clutch (studies/run_verdict.hpp's block)
// and `verdict` with the text `clutch` naming the worst.

#include <cstddef>
#include <string>
#include <vector>

#include "dynamics/recording.hpp"
#include "studies/run_verdict.hpp"

namespace shudder::studies {

/// The lowest frequency a network clutch's oscillation is searched from, Hz (header).
inline constexpr double kNetworkMinFrequency_Hz = 2.0;
/// Fewest samples judged (the detector's own minimum, analysis/shudder_detection.hpp).
inline constexpr std::size_t kMinJudgedSamples = 64;

struct ClutchVerdict {
  std::string clutch;
  bool judged = false;
  std::string reason;  // why not judged
  studies::RunVerdict verdict;
};

/// Judges clutch `clutch` of a network recording sampled at `sample_rate_Hz` on the torque
/// channel `torque_signal` (its own CLUTCH.torque_Nm, or a shaft's: ClutchSpec::judged_on); the
/// verdict's prediction is left for studies/clutch_prediction.hpp.
ClutchVerdict judge_clutch(const dynamics::Recording& rec, const std::string& clutch, const std::string& torque_signal,
                           double sample_rate_Hz);

/// Rank of a verdict for the run's verdict (none 0, vibration 1, stick_slip 2).
int verdict_rank(const analysis::ShudderResult& r);

/// Index of the run's verdict among `verdicts` (header), -1 if none was judged.
int worst_verdict(const std::vector<ClutchVerdict>& verdicts);

/// Adds the blocks `verdict.CLUTCH` and `verdict` (header) to `rec`; `none_reason` is the run's
/// reason when no clutch was judged.
void add_verdict_blocks(dynamics::Recording& rec, const std::vector<ClutchVerdict>& verdicts, int worst,
                        const std::string& none_reason);

}  // namespace shudder::studies
