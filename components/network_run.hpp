#pragma once
// Runs a network (components/network_builder.hpp) and judges every clutch in it.
//
// Integration: dynamics::Simulation (dopri5, exact stick/slip events) with every wet clutch
// coupled multi-rate (rig_models/multirate_clutch.hpp: each clutch's thermal model advanced
// every thermal step with the friction heat its own contact accumulated, its ring temperatures
// on a first-order hold); the stepper restarts at every jump of an input signal. A network
// without wet clutches is integrated in one stretch between those jumps.
//
// Recording (docs/network_format.md "Output"): `time_s`, then channels named
// `<component>.<quantity>_<unit>`, e.g. `launch_clutch.slip_rpm`; summary scalars (the energy
// account; per clutch its friction work, per wet clutch its peak interface temperature); a
// verdict block per clutch (`verdict.<clutch>`: rig_models/run_verdict.hpp's block judged on that
// clutch's torque and slip) and the run's `verdict` block, the worst clutch's verdict with text
// `clutch` naming it (stick_slip over vibration over none; between equals, the larger amplitude).
//
// Judging a clutch (analysis/shudder_detection.hpp's detector) covers its LOADED WINDOW: from
// its first sample with normal force > 0 to its last sample slipping under load. A launch
// judders while the clutch slips and then locks; the lock-up that ends an engagement, and what
// follows it, is no stick-slip, while sticking again and again inside the window is. The search
// starts at max(2 Hz, 3 / window length): a car's shuffle and take-up modes lie at a few Hz, and
// a frequency counts only if the window holds three of its cycles. A window of fewer than
// kMinJudgedSamples samples is "not judged", with the reason. An oscillation counts only if it
// lasts to the window's end (the last two periods' amplitude at least half the largest period's,
// components/transient_oscillation.hpp): a ringing that dies out while the clutch still slips is
// the drivetrain answering a step; a judder lasts until the clutch locks or opens.

#include <cstddef>
#include <string>
#include <vector>

#include "components/network_spec.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/run_verdict.hpp"

namespace shudder::components {

/// The lowest frequency a network clutch's oscillation is searched from, Hz (header).
inline constexpr double kNetworkMinFrequency_Hz = 2.0;
/// Cycles of the lowest searched frequency the loaded window must hold.
inline constexpr double kMinJudgedCycles = 3.0;
/// Fewest samples judged (the detector's own minimum, analysis/shudder_detection.hpp).
inline constexpr std::size_t kMinJudgedSamples = 64;

struct ClutchVerdict {
  std::string clutch;
  bool judged = false;
  std::string reason;  // why not judged
  rig_models::RunVerdict verdict;
};

struct NetworkRun {
  dynamics::Recording recording;
  std::vector<ClutchVerdict> verdicts;  // one per clutch, in the spec's order
  int worst = -1;                       // index into verdicts of the run's verdict; -1: no clutch
  double energy_imbalance_J = 0.0, energy_scale_J = 0.0;
};

/// Builds, runs and judges; throws NetworkError (bad network), std::runtime_error (numerical
/// failure).
NetworkRun run_network(const NetworkSpec& spec);

/// Rank of a verdict for the run's verdict (none 0, vibration 1, stick_slip 2).
int verdict_rank(const analysis::ShudderResult& r);

}  // namespace shudder::components
