#include "studies/clutch_judgement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <utility>

#include "dynamics/signal_names.hpp"
#include "studies/recording_detection.hpp"

namespace shudder::studies {

namespace {

const dynamics::Signal& signal(const dynamics::Recording& rec, const std::string& name) {
  const auto* s = rec.find(name);
  if (!s) throw std::logic_error("network run: channel " + name + " missing");
  return *s;
}

// The part of the record a clutch is judged on: from its first loaded sample (normal force > 0)
// to its last sample slipping under load. The lock-up that ends an engagement, and the time the
// clutch stays open or locked after it, are not judged: a single lock-up is no stick-slip.
std::pair<std::size_t, std::size_t> loaded_window(const std::vector<double>& stuck, const std::vector<double>& force) {
  std::size_t i0 = 0;
  while (i0 < force.size() && !(force[i0] > 0)) ++i0;
  std::size_t i1 = force.size();
  while (i1 > i0 && !(force[i1 - 1] > 0 && stuck[i1 - 1] < 0.5)) --i1;
  return {i0, i1};
}

}  // namespace

int verdict_rank(const analysis::ShudderResult& r) {
  switch (r.verdict) {
    case analysis::Verdict::kNone: return 0;
    case analysis::Verdict::kVibration: return 1;
    case analysis::Verdict::kStickSlip: return 2;
  }
  return 0;
}

ClutchVerdict judge_clutch(const dynamics::Recording& rec, const std::string& clutch, const std::string& torque,
                           double sample_rate_Hz) {
  const auto& time = signal(rec, std::string(dynamics::signal_names::kTime));
  ClutchVerdict cv;
  cv.clutch = clutch;
  const std::string slip = clutch + ".slip_rpm";
  const auto& stuck = signal(rec, clutch + ".stuck").values;
  const auto& force = signal(rec, clutch + ".normal_force_N").values;
  const auto window = loaded_window(stuck, force);
  const std::size_t i0 = window.first, i1 = window.second;  // plain names: lambdas below capture them
  const double span_s = i1 > i0 ? time.values[i1 - 1] - time.values[i0] : 0.0;
  if (i1 - i0 < kMinJudgedSamples) {
    cv.reason = i1 > i0 ? "it slips under load for only " + std::to_string(span_s) + " s (" + std::to_string(i1 - i0) +
                              " samples; at least " + std::to_string(kMinJudgedSamples) + " are judged)"
                        : "it never slips under load";
  } else {
    studies::RecordingDetection d;
    d.torque_signal = torque;
    d.slip_signal = slip;
    const auto part = [&](const std::vector<double>& v) { return std::span<const double>(v).subspan(i0, i1 - i0); };
    d.input.time_s = part(time.values);
    d.input.torque_Nm = part(signal(rec, torque).values);
    d.input.slip_rpm = part(signal(rec, slip).values);
    d.input.stuck = part(stuck);
    d.input.normal_force_N = part(force);
    if (const auto* s = rec.find(clutch + ".interface_mean_temp_C")) d.input.interface_temp_C = part(s->values);
    d.settings.onset_definition = analysis::OnsetDefinition::kThresholdCrossing;
    d.settings.min_frequency_Hz = std::max(kNetworkMinFrequency_Hz, kMinJudgedCycles / span_s);
    if (d.settings.min_frequency_Hz >= 0.4 * sample_rate_Hz) {
      cv.reason = "its loaded slip (" + std::to_string(span_s) + " s) is too short to hold " +
                  std::to_string(static_cast<int>(kMinJudgedCycles)) +
                  " cycles below 0.4 x the sample rate (the highest frequency judged)";
    } else {
      d.settings.max_frequency_Hz = std::min(d.settings.max_frequency_Hz, 0.4 * sample_rate_Hz);
      try {
        cv.verdict = studies::judge_detection(d);
        cv.judged = true;
        keep_if_repeated(d, cv.verdict.judged);
      } catch (const std::invalid_argument& err) {
        cv.reason = err.what();
      }
    }
  }
  return cv;
}

int worst_verdict(const std::vector<ClutchVerdict>& verdicts) {
  int worst = -1;
  for (std::size_t i = 0; i < verdicts.size(); ++i) {
    const auto& v = verdicts[i];
    if (!v.judged) continue;
    if (worst < 0) {
      worst = static_cast<int>(i);
      continue;
    }
    const auto& w = verdicts[static_cast<std::size_t>(worst)].verdict.judged;
    const int rv = verdict_rank(v.verdict.judged), rw = verdict_rank(w);
    if (rv > rw || (rv == rw && rv > 0 && v.verdict.judged.amplitude_Nm > w.amplitude_Nm)) worst = static_cast<int>(i);
  }
  return worst;
}

void add_verdict_blocks(dynamics::Recording& rec, const std::vector<ClutchVerdict>& verdicts, int worst,
                        const std::string& none_reason) {
  for (const auto& cv : verdicts) {
    if (cv.judged) {
      auto block = studies::verdict_block(cv.verdict);
      block.name = "verdict." + cv.clutch;
      block.description = "clutch " + cv.clutch + ": " + block.description;
      rec.blocks.push_back(std::move(block));
    } else {
      auto block = studies::not_judged_block(cv.reason);
      block.name = "verdict." + cv.clutch;
      rec.blocks.push_back(std::move(block));
    }
  }
  if (worst >= 0) {
    auto block = studies::verdict_block(verdicts[static_cast<std::size_t>(worst)].verdict);
    block.texts.push_back({"clutch", verdicts[static_cast<std::size_t>(worst)].clutch});
    block.description = "the run's verdict: the worst of its clutches' verdicts (text `clutch` names it)";
    rec.blocks.push_back(std::move(block));
  } else {
    auto block = studies::not_judged_block(none_reason);
    rec.blocks.push_back(std::move(block));
  }
}

}  // namespace shudder::studies
