#include "studies/run_verdict.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "studies/recording_detection.hpp"
#include "studies/rig_stability.hpp"
#include "core/nan.hpp"

namespace shudder::studies {

namespace {

// Mean of x over the samples whose time lies in [from, to]; NaN for an absent signal.
double window_mean(std::span<const double> t, std::span<const double> x, double from_s, double to_s) {
  if (x.empty() || x.size() != t.size()) return kNaN;
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= from_s && t[i] <= to_s) {
      sum += x[i];
      ++n;
    }
  return n > 0 ? sum / static_cast<double>(n) : kNaN;
}

}  // namespace

Prediction Prediction::none(const std::string& why) {
  Prediction p;
  p.method = "not predicted: " + why;
  return p;
}

RunVerdict judge_run(const dynamics::Recording& rec) {
  const auto detection = recording_detection(rec);
  if (!detection) throw std::invalid_argument("the recording has no time, torque or slip channel to judge");
  return judge_detection(*detection);
}

RunVerdict judge_detection(const RecordingDetection& detection) {
  RunVerdict v;
  v.torque_signal = std::string(detection.torque_signal);
  v.slip_signal = std::string(detection.slip_signal);
  v.judged = judge_recording(detection);

  // The judged window: the oscillating part when there is an oscillation, else the whole record.
  const auto& in = detection.input;
  const bool oscillating = v.judged.verdict != analysis::Verdict::kNone;
  v.window.what = oscillating ? "oscillating part" : "whole run";
  v.window.from_s = oscillating ? v.judged.oscillating_from_s : in.time_s.front();
  v.window.to_s = oscillating ? v.judged.oscillating_to_s : in.time_s.back();
  const auto mean = [&](std::span<const double> x) {
    return window_mean(in.time_s, x, v.window.from_s, v.window.to_s);
  };
  v.window.slip_rpm = mean(in.slip_rpm);
  v.window.interface_temp_C = mean(in.interface_temp_C);
  v.window.normal_force_N = mean(in.normal_force_N);
  return v;
}

Prediction predict_rig(const rig_models::RigParams& params, const clutch::WetClutch& clutch, const OperatingWindow& w) {
  if (!(w.normal_force_N > 0)) return Prediction::none("the clutch is not loaded over the judged window");
  if (!std::isfinite(w.interface_temp_C)) return Prediction::none("the interface temperature is not recorded");
  analysis::StabilityPoint p;
  try {
    p = rig_stability(params, clutch, w.normal_force_N, w.slip_rpm, w.interface_temp_C);
  } catch (const std::invalid_argument& e) {
    return Prediction::none(e.what());
  }
  Prediction out;
  out.made = true;
  out.method =
      "rig linear stability at the operating point (isothermal friction slope, every ring at the mean "
      "interface temperature)";
  out.margin_per_s = p.margin_per_s;
  out.oscillatory_margin_per_s = p.oscillatory_margin_per_s;
  out.frequency_Hz = p.oscillatory_frequency_Hz;
  return out;
}

dynamics::ResultBlock not_judged_block(const std::string& why) {
  dynamics::ResultBlock b;
  b.name = kVerdictBlock;
  b.description = "the run could not be judged for shudder";
  b.texts = {{"verdict", "not_judged"}, {"reason", why}};
  return b;
}

dynamics::ResultBlock verdict_block(const RunVerdict& v) {
  const analysis::ShudderResult& r = v.judged;
  dynamics::ResultBlock b;
  b.name = kVerdictBlock;
  b.description =
      "shudder verdict of the run (analysis/shudder_detection on the judged channels) and the linear "
      "stability predicted at the mean operating point of the judged window";
  b.texts = {{"verdict", std::string(analysis::to_string(r.verdict))},
             {"judged_signals", v.torque_signal + ", " + v.slip_signal},
             {"operating_window", v.window.what},
             {"prediction", v.prediction.method}};
  b.scalars = {{"verdict_code", "1", static_cast<double>(r.verdict)},
               {"frequency_Hz", "Hz", r.frequency_Hz},
               {"peak_frequency_Hz", "Hz", r.peak_frequency_Hz},
               {"amplitude_Nm", "N m", r.amplitude_Nm},
               {"threshold_Nm", "N m", r.threshold_Nm},
               {"onset_time_s", "s", r.onset_time_s},
               {"window_from_s", "s", v.window.from_s},
               {"window_to_s", "s", v.window.to_s},
               {"slip_rpm", "rpm", v.window.slip_rpm},
               {"interface_temp_C", "degC", v.window.interface_temp_C},
               {"normal_force_N", "N", v.window.normal_force_N},
               {"predicted_margin_per_s", "1/s", v.prediction.margin_per_s},
               {"predicted_oscillatory_margin_per_s", "1/s", v.prediction.oscillatory_margin_per_s},
               {"predicted_frequency_Hz", "Hz", v.prediction.frequency_Hz}};
  return b;
}

}  // namespace shudder::studies
