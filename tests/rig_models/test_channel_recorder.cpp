// The runners' recorder (rig_models/channel_recorder.hpp): channels are declared once and appear
// in that order with their units; interpolated channels are linear in time across slow steps, so
// a quantity that is itself linear in time is reproduced exactly (to round-off).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/signal_names.hpp"
#include "rig_models/channel_recorder.hpp"

namespace shudder::rig_models {
namespace {

// Fast side: the sample time only; slow side: a state known at slow-step ends.
struct SlowState {
  double t_s;
  double ramp;  // 3 + 2 t
};
using Recorder = ChannelRecorder<double, SlowState>;

TEST(ChannelRecorder, ChannelsAppearOnceInDeclarationOrderWithTheirUnits) {
  dynamics::Recording rec;
  Recorder recorder(rec, {Recorder::sampled(dynamics::signal_names::kTime, "s", [](double t) { return t; }),
                          Recorder::interpolated("ramp", "degC", [](const SlowState& s) { return s.ramp; }),
                          Recorder::sampled("twice_t", "N m", [](double t) { return 2 * t; })});
  ASSERT_EQ(rec.signals.size(), 3u);
  EXPECT_EQ(rec.signals[0].name, "time_s");
  EXPECT_EQ(rec.signals[0].units, "s");
  EXPECT_EQ(rec.signals[1].name, "ramp");
  EXPECT_EQ(rec.signals[1].units, "degC");
  EXPECT_EQ(rec.signals[2].name, "twice_t");
  EXPECT_EQ(rec.signals[2].units, "N m");
}

// Samples every 0.1 s, slow steps of 0.25 s (not aligned with the samples): each interpolated
// sample equals the ramp 3 + 2 t. Tolerance 1e-14 relative: a few roundings of values ~5.
TEST(ChannelRecorder, InterpolationAcrossSlowStepsReproducesALinearRampExactly) {
  const auto ramp = [](double t) { return 3.0 + 2.0 * t; };
  dynamics::Recording rec;
  Recorder recorder(rec, {Recorder::sampled(dynamics::signal_names::kTime, "s", [](double t) { return t; }),
                          Recorder::interpolated("ramp", "1", [](const SlowState& s) { return s.ramp; })});
  recorder.sample(0.0);
  recorder.start(SlowState{0.0, ramp(0.0)});
  int next = 1;
  for (int step = 1; step <= 8; ++step) {
    const double ta = 0.25 * (step - 1), tb = 0.25 * step;
    for (; 0.1 * next <= tb + 1e-12; ++next) recorder.sample(0.1 * next);
    recorder.step(SlowState{tb, ramp(tb)}, ta, tb);
  }
  const auto& t = rec.find("time_s")->values;
  const auto& x = rec.find("ramp")->values;
  ASSERT_EQ(t.size(), 21u);
  ASSERT_EQ(x.size(), t.size());
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(x[k], ramp(t[k]), 1e-14 * ramp(t[k])) << "t = " << t[k];
}

// A step of zero length hands over its end values (w = 1), as at the start of a run.
TEST(ChannelRecorder, AnEmptyStepGivesTheEndValues) {
  dynamics::Recording rec;
  Recorder recorder(rec, {Recorder::sampled(dynamics::signal_names::kTime, "s", [](double t) { return t; }),
                          Recorder::interpolated("ramp", "1", [](const SlowState& s) { return s.ramp; })});
  recorder.sample(0.0);
  recorder.start(SlowState{0.0, 7.0});
  recorder.sample(1.0);
  recorder.step(SlowState{1.0, 11.0}, 1.0, 1.0);
  EXPECT_EQ(rec.find("ramp")->values, (std::vector<double>{7.0, 11.0}));
}

TEST(ChannelRecorder, TheFirstChannelMustBeTheSampledTime) {
  dynamics::Recording rec;
  EXPECT_THROW(Recorder(rec, {Recorder::interpolated("ramp", "1", [](const SlowState& s) { return s.ramp; })}),
               std::logic_error);
  EXPECT_THROW(Recorder(rec, {Recorder::interpolated("time_s", "s", [](const SlowState& s) { return s.t_s; })}),
               std::logic_error);
}

}  // namespace
}  // namespace shudder::rig_models
