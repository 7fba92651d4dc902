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

// 10 s at 200 Hz; torque = 100 + 20 e^(−t/τ) sin(2π f t) N m on `torque_name` (τ = ∞: steady),
// a steady 30 rpm slip.
Recording oscillating(const char* torque_name, const char* slip_name, double f_Hz, double decay_time_s = INFINITY) {
  std::vector<double> t, torque, slip;
  for (int i = 0; i <= 2000; ++i) {
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

// The sustained-oscillation rule: a ringing with τ = 1 s has e^(−9) ≈ 1e-4 of its amplitude
// left over the last tenth of the record, far under half — no verdict; the steady 3 Hz
// oscillation above keeps its full amplitude — a verdict. The plain detector sees both.
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
