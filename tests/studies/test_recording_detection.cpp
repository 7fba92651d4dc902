// One definition of how a recording is judged (studies/recording_detection.hpp): the run
// that writes a driveline's judder verdict and a later plot of its file must use the same
// channels and band. A coupling oscillating at 3 Hz — inside the driveline's band (from 2 Hz),
// outside the rig's default (from 5 Hz) — is the case that tells them apart.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/shudder_detection.hpp"
#include "studies/recording_detection.hpp"

namespace {

using shudder::dynamics::Recording;
using shudder::studies::recording_detection;

// `duration_s` (10 s) at 200 Hz; torque = 100 + 20 e^(−t/τ) sin(2π f t) N m on `torque_name`
// (τ = ∞: steady), a steady 30 rpm slip.
Recording oscillating(const char* torque_name, const char* slip_name, double f_Hz, double decay_time_s = INFINITY,
                      double duration_s = 10.0) {
  std::vector<double> t, torque, slip;
  for (int i = 0; i <= static_cast<int>(std::lround(200.0 * duration_s)); ++i) {
    t.push_back(i / 200.0);
    torque.push_back(100.0 +
                     20.0 * std::exp(-t.back() / decay_time_s) * std::sin(2.0 * std::numbers::pi * f_Hz * t.back()));
    slip.push_back(30.0);
  }
  Recording rec;
  rec.add_signal("time_s", "s").values = t;
  rec.add_signal(torque_name, "N m").values = torque;
  rec.add_signal(slip_name, "rpm").values = slip;
  return rec;
}

TEST(RecordingDetection, ADrivelineIsJudgedOnItsCouplingFromTwoHertz) {
  const Recording rec = oscillating("coupling_torque_Nm", "coupling_slip_rpm", 3.0);
  const auto d = recording_detection(rec);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->torque_signal, "coupling_torque_Nm");
  EXPECT_EQ(d->input.torque_Nm.data(), rec.find("coupling_torque_Nm")->values.data());
  EXPECT_EQ(d->input.slip_rpm.data(), rec.find("coupling_slip_rpm")->values.data());
  EXPECT_EQ(d->settings.min_frequency_Hz, 2.0);
  const auto r = shudder::analysis::detect_shudder(d->input, d->settings);
  EXPECT_NE(r.verdict, shudder::analysis::Verdict::kNone);
  // Frequency resolution: the detector interpolates its peak; 2 % of 3 Hz is well inside
  // one Welch bin (200 Hz / 2048 ≈ 0.1 Hz) of the true line.
  EXPECT_NEAR(r.frequency_Hz, 3.0, 0.06);
  // The rig's default band starts at 5 Hz and cannot see it: the reason one definition matters.
  const auto rig_band = shudder::analysis::detect_shudder(d->input, shudder::analysis::DetectionSettings{});
  EXPECT_FALSE(std::abs(rig_band.frequency_Hz - 3.0) < 0.06 && rig_band.verdict != shudder::analysis::Verdict::kNone);
}

// The sustained-oscillation rule: a ringing with τ = 1 s falls 1 / (f τ) = 33 % per period, ten
// times the rule's limit — no verdict; the steady 3 Hz oscillation above keeps its amplitude —
// a verdict. The plain detector sees both.
TEST(RecordingDetection, ADrivelineRingingThatDiesOutIsNoJudder) {
  const Recording ringing = oscillating("coupling_torque_Nm", "coupling_slip_rpm", 3.0, 1.0);
  const auto d = recording_detection(ringing);
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->sustained_only);
  EXPECT_NE(shudder::analysis::detect_shudder(d->input, d->settings).verdict, shudder::analysis::Verdict::kNone);
  EXPECT_EQ(shudder::studies::judge_recording(*d).verdict, shudder::analysis::Verdict::kNone);

  const Recording steady = oscillating("coupling_torque_Nm", "coupling_slip_rpm", 3.0);
  EXPECT_NE(shudder::studies::judge_recording(*recording_detection(steady)).verdict, shudder::analysis::Verdict::kNone);
}

// The rule is the envelope's decay, not the record's length: a mode of damping ratio ζ rings
// with the envelope e^(−ζ ω t), i.e. τ = 1 / (2π f ζ). At 3 Hz, ζ = 0.02 (τ = 2.65 s) falls
// 12 % per period, so it is no judder in a 3 s record that ends while it still rings at a
// third of its start, as in a 10 s one. ζ = 0.001 (τ = 53 s, 0.6 % per period, under the
// rule's 0.5 % of critical, 3.1 % per period) is an oscillation that holds: a verdict in both.
TEST(RecordingDetection, ARingingIsJudgedByItsDecayNotByTheRecordsLength) {
  const double f = 3.0;
  const auto tau = [&](double zeta) { return 1.0 / (2.0 * std::numbers::pi * f * zeta); };
  for (const double duration : {3.0, 10.0}) {
    const Recording ringing = oscillating("coupling_torque_Nm", "coupling_slip_rpm", f, tau(0.02), duration);
    EXPECT_EQ(shudder::studies::judge_recording(*recording_detection(ringing)).verdict,
              shudder::analysis::Verdict::kNone)
        << duration << " s";
    const Recording holding = oscillating("coupling_torque_Nm", "coupling_slip_rpm", f, tau(0.001), duration);
    EXPECT_NE(shudder::studies::judge_recording(*recording_detection(holding)).verdict,
              shudder::analysis::Verdict::kNone)
        << duration << " s";
  }
}

// A network clutch is judged by the same rule (studies/clutch_judgement.hpp calls it).
TEST(RecordingDetection, KeepIfRepeatedSetsADecayingVibrationToNoneAndKeepsWhatRang) {
  const Recording ringing = oscillating("torque_Nm", "slip_rpm", 3.0, 1.0);
  auto d = *recording_detection(ringing);
  d.settings.min_frequency_Hz = 2.0;
  shudder::analysis::ShudderResult r = shudder::analysis::detect_shudder(d.input, d.settings);
  ASSERT_EQ(r.verdict, shudder::analysis::Verdict::kVibration);
  const double amplitude = r.amplitude_Nm, peak = r.peak_frequency_Hz;
  shudder::studies::keep_if_repeated(d, r);
  EXPECT_EQ(r.verdict, shudder::analysis::Verdict::kNone);
  EXPECT_TRUE(std::isnan(r.frequency_Hz));
  EXPECT_TRUE(std::isnan(r.onset_time_s));
  EXPECT_EQ(r.amplitude_Nm, amplitude);
  EXPECT_EQ(r.peak_frequency_Hz, peak);
}

TEST(RecordingDetection, ARigIsJudgedOnItsTorqueCellAndSlip) {
  const Recording rec = oscillating("torque_Nm", "slip_rpm", 150.0);
  const auto d = recording_detection(rec);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->torque_signal, "torque_Nm");
  EXPECT_EQ(d->input.slip_rpm.data(), rec.find("slip_rpm")->values.data());
  EXPECT_EQ(d->settings.min_frequency_Hz, shudder::analysis::DetectionSettings{}.min_frequency_Hz);
  EXPECT_FALSE(d->sustained_only);
}

TEST(RecordingDetection, PrescribedSlipUsesTheImposedSpeedAsSlip) {
  const Recording rec = oscillating("torque_Nm", "speed_rpm", 50.0);
  const auto d = recording_detection(rec);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->input.slip_rpm.data(), rec.find("speed_rpm")->values.data());
}

TEST(RecordingDetection, NothingToJudgeWithoutTorqueOrSlip) {
  Recording rec;
  rec.add_signal("time_s", "s").values = {0.0, 1.0};
  rec.add_signal("temp_C", "degC").values = {20.0, 21.0};
  EXPECT_FALSE(recording_detection(rec));
}

}  // namespace
