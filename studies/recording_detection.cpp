#include "studies/recording_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "dynamics/signal_names.hpp"

namespace shudder::studies {

namespace sn = dynamics::signal_names;

namespace {

// Half peak-to-peak of x minus its centred one-period moving mean, over the last
// max(2 periods, a tenth) of the record (uniform sampling).
double final_oscillation_amplitude_Nm(std::span<const double> t, std::span<const double> x, double period_s) {
  const std::size_t n = t.size();
  if (n < 4) return 0.0;
  const double dt = (t.back() - t.front()) / static_cast<double>(n - 1);
  const std::size_t half = std::max<std::size_t>(1, static_cast<std::size_t>(0.5 * period_s / dt));
  const double span_s = std::max(2.0 * period_s, 0.1 * (t.back() - t.front()));
  const std::size_t from = n - std::min(n, static_cast<std::size_t>(span_s / dt) + half);
  double lo = 0, hi = 0;
  bool any = false;
  for (std::size_t i = std::max(from, half); i + half < n; ++i) {
    double mean = 0;
    for (std::size_t j = i - half; j <= i + half; ++j) mean += x[j];
    const double r = x[i] - mean / static_cast<double>(2 * half + 1);
    lo = any ? std::min(lo, r) : r;
    hi = any ? std::max(hi, r) : r;
    any = true;
  }
  return any ? 0.5 * (hi - lo) : 0.0;
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

analysis::ShudderResult judge_recording(const RecordingDetection& d) {
  analysis::ShudderResult r = analysis::detect_shudder(d.input, d.settings);
  if (d.sustained_only && r.verdict != analysis::Verdict::kNone && std::isfinite(r.frequency_Hz) &&
      r.frequency_Hz > 0) {
    const double end_amplitude =
        final_oscillation_amplitude_Nm(d.input.time_s, d.input.torque_Nm, 1.0 / r.frequency_Hz);
    if (end_amplitude < 0.5 * r.amplitude_Nm) {
      // No verdict, so none of its timing either (ShudderResult's convention for none):
      // peak_frequency_Hz and amplitude_Nm still say what rang.
      constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
      r.verdict = analysis::Verdict::kNone;
      r.frequency_Hz = r.onset_time_s = r.growth_rate_per_s = r.growth_acceleration_per_s2 = kNaN;
      r.at_onset = {kNaN, kNaN, kNaN, kNaN};
    }
  }
  return r;
}

}  // namespace shudder::studies
