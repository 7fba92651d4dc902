#include "studies/recording_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "dynamics/signal_names.hpp"
#include "studies/transient_oscillation.hpp"

namespace shudder::studies {

namespace sn = dynamics::signal_names;

namespace {

// The envelope decay, as a damping ratio, below which an oscillation holds (header).
constexpr double kSustainedDampingRatio = 0.005;

// Whether the oscillation at `frequency_Hz` holds: its per-period amplitudes (the last period
// first) fall from the largest to the mean of the last two by less per period than a mode of
// damping ratio kSustainedDampingRatio would, exp(-2 pi zeta). With the largest among the last
// two periods it holds or grows.
bool envelope_holds(std::span<const double> time_s, std::span<const double> torque_Nm, double frequency_Hz) {
  const auto periods = period_amplitudes_from_end(time_s, torque_Nm, frequency_Hz);
  if (periods.size() < 2) return false;
  const auto largest = std::max_element(periods.begin(), periods.end());
  const auto k = static_cast<double>(largest - periods.begin());
  if (k <= 1.0) return true;
  const double end = 0.5 * (periods[0] + periods[1]);
  if (!(end > 0.0)) return false;
  // The end's mean sits half a period from the last period's start: k - 0.5 periods of decay.
  const double decay_per_period = std::log(*largest / end) / (k - 0.5);
  return decay_per_period < 2.0 * std::numbers::pi * kSustainedDampingRatio;
}

}  // namespace

std::string_view judged_torque_signal(const dynamics::Recording& rec) {
  if (rec.find(sn::kCouplingTorque)) return sn::kCouplingTorque;
  if (network_verdict_clutch(rec)) {
    // The verdict's judged torque: the clutch's own or the shaft it is judged on.
    const auto* judged = rec.find_block("verdict")->find_text("judged_signals");
    const std::string name = judged ? judged->value.substr(0, judged->value.find(", ")) : "";
    if (const auto* s = rec.find(name)) return s->name;
  }
  return sn::kTorque;
}

const std::string* network_verdict_clutch(const dynamics::Recording& rec) {
  if (rec.find(sn::kTorque) || rec.find(sn::kCouplingTorque)) return nullptr;
  const auto* verdict = rec.find_block("verdict");
  const auto* clutch = verdict ? verdict->find_text("clutch") : nullptr;
  return clutch ? &clutch->value : nullptr;
}

std::optional<RecordingDetection> recording_detection(const dynamics::Recording& rec) {
  const bool driveline = rec.find(sn::kCouplingTorque) != nullptr;
  const auto* time = rec.find(sn::kTime);
  const auto* torque = rec.find(judged_torque_signal(rec));
  std::string_view slip_signal = driveline ? sn::kCouplingSlip : sn::kSlip;
  if (!driveline && !rec.find(slip_signal)) slip_signal = sn::kSpeed;
  if (const auto* clutch = network_verdict_clutch(rec))
    if (const auto* s = rec.find(*clutch + ".slip_rpm")) slip_signal = s->name;
  const auto* slip = rec.find(slip_signal);
  if (!time || !torque || !slip) return std::nullopt;

  RecordingDetection d;
  d.torque_signal = judged_torque_signal(rec);
  d.slip_signal = slip_signal;
  d.input.time_s = time->values;
  d.input.torque_Nm = torque->values;
  d.input.slip_rpm = slip->values;
  if (const auto* s = rec.find(sn::kStuck)) d.input.stuck = s->values;
  if (const auto* s = rec.find(sn::kInterfaceMeanTemp)) d.input.interface_temp_C = s->values;
  if (const auto* s = rec.find(driveline ? sn::kClampForce : sn::kNormalForce)) d.input.normal_force_N = s->values;
  // A run's onset: the oscillation reaching the verdict's threshold (the detector's threshold-crossing onset),
  // not set by the start transient.
  d.settings.onset_definition = analysis::OnsetDefinition::kThresholdCrossing;
  if (driveline) {
    d.settings.min_frequency_Hz = 2.0;
    d.sustained_only = true;
  }
  return d;
}

void keep_if_repeated(const RecordingDetection& d, analysis::ShudderResult& r) {
  if (r.verdict == analysis::Verdict::kNone || !(std::isfinite(r.frequency_Hz) && r.frequency_Hz > 0)) return;
  const bool stuck_recorded = !d.input.stuck.empty();
  if (r.verdict == analysis::Verdict::kStickSlip && stuck_recorded && stick_onsets(d.input.stuck) >= 2) return;
  if (r.verdict == analysis::Verdict::kVibration || !stuck_recorded) {
    const int swings = oscillation_swings(d.input.time_s, d.input.torque_Nm, r.frequency_Hz, 0.5 * r.threshold_Nm);
    const bool lasts = envelope_holds(d.input.time_s, d.input.torque_Nm, r.frequency_Hz);
    if (swings >= static_cast<int>(2 * kMinJudgedCycles) && lasts) return;
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  r.verdict = analysis::Verdict::kNone;
  r.frequency_Hz = r.onset_time_s = r.growth_rate_per_s = r.growth_acceleration_per_s2 = kNaN;
  r.at_onset = {kNaN, kNaN, kNaN, kNaN};
}

analysis::ShudderResult judge_recording(const RecordingDetection& d) {
  analysis::ShudderResult r = analysis::detect_shudder(d.input, d.settings);
  if (d.sustained_only) keep_if_repeated(d, r);
  return r;
}

}  // namespace shudder::studies
