// The runners' recorder (components/channel_recorder.hpp): channels are declared once and appear
// in that order with their units; interpolated channels are linear in time across slow steps, so
// a quantity that is itself linear in time is reproduced exactly (to round-off); refined channels
// are read afresh inside a step when the step is given a way to evaluate the slow state there.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/signal_names.hpp"
#include "components/channel_recorder.hpp"

namespace shudder::components {
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

// Refined channels. The slow quantity is t², not linear in time, so a chord between a step's
// ends and a fresh evaluation inside the step differ: by w (1 − w) h² at w, 0.047 at w = 1/4 and
// 0.0625 at w = 1/2 for steps of h = 0.5 s. Samples every 0.125 s and steps of 0.5 s are exact in
// binary, so the samples at a step's ends have w = 1 exactly and those inside w = 1/4, 1/2, 3/4.
struct Curve {
  double t_s;
  double square;  // t²
};
using CurveRecorder = ChannelRecorder<double, Curve>;
constexpr double kSampleStep = 0.125, kSlowStep = 0.5;
constexpr int kSlowSteps = 4;

Curve curve(double t) { return {t, t * t}; }

// A recorder with an interpolated and a refined channel of the same quantity t², driven over
// kSlowSteps steps; `inside` (may be empty) is passed to every step.
dynamics::Recording record_square(const CurveRecorder::Inside& inside) {
  dynamics::Recording rec;
  CurveRecorder recorder(
      rec, {CurveRecorder::sampled(dynamics::signal_names::kTime, "s", [](double t) { return t; }),
            CurveRecorder::interpolated("square_interpolated", "s2", [](const Curve& c) { return c.square; }),
            CurveRecorder::refined("square_refined", "s2", [](const Curve& c) { return c.square; })});
  recorder.sample(0.0);
  recorder.start(curve(0.0));
  int next = 1;
  for (int step = 1; step <= kSlowSteps; ++step) {
    const double ta = kSlowStep * (step - 1), tb = kSlowStep * step;
    for (; kSampleStep * next <= tb; ++next) recorder.sample(kSampleStep * next);
    recorder.step(curve(tb), ta, tb, inside);
  }
  return rec;
}

// The straight line between the ends of the slow step around t (the step whose end is at or
// after t), as the recorder interpolates.
double chord_of_square(double t) {
  const double tb = kSlowStep * std::ceil(t / kSlowStep), ta = std::max(tb - kSlowStep, 0.0);
  const double w = tb > ta ? (t - ta) / (tb - ta) : 1.0;
  return (1 - w) * ta * ta + w * tb * tb;
}

bool at_a_step_end(double t) { return std::fmod(t, kSlowStep) == 0.0; }

// With `inside`, the refined channel is t² at every sample: fresh inside a step, the step's end
// value at its ends (where t² is the end value). The interpolated channel stays on the chord,
// which inside a step lies 0.047 to 0.0625 above t² (the gap is asserted, so a recorder that
// refined every channel, or none, fails here). Tolerance 1e-14 relative: a few roundings of
// values up to 4.
TEST(ChannelRecorder, ARefinedChannelIsFreshInsideAStepWhileAnInterpolatedOneStaysOnTheChord) {
  const dynamics::Recording rec = record_square([](double t, double) { return curve(t); });
  const auto& t = rec.find("time_s")->values;
  const auto& lin = rec.find("square_interpolated")->values;
  const auto& fine = rec.find("square_refined")->values;
  ASSERT_EQ(t.size(), 17u);
  ASSERT_EQ(lin.size(), t.size());
  ASSERT_EQ(fine.size(), t.size());
  int inside = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double exact = t[k] * t[k];
    EXPECT_NEAR(fine[k], exact, 1e-14 * (1 + exact)) << "t = " << t[k];
    EXPECT_NEAR(lin[k], chord_of_square(t[k]), 1e-14 * (1 + exact)) << "t = " << t[k];
    if (at_a_step_end(t[k])) {
      EXPECT_EQ(fine[k], lin[k]) << "t = " << t[k];  // both the end's value
    } else {
      ++inside;
      EXPECT_GT(lin[k] - fine[k], 0.04) << "t = " << t[k];
    }
  }
  EXPECT_EQ(inside, 3 * kSlowSteps);
}

// `inside` is called once for each sample strictly inside a step, in order, with that sample's
// time and its w, and never for a sample at a step's end: the calls are exactly the 12 inside
// samples (w = 1/4, 1/2, 3/4, exact in binary, compared with ==).
TEST(ChannelRecorder, InsideIsCalledOncePerSampleInsideAStepAndNeverAtItsEnds) {
  std::vector<double> call_t, call_w;
  const dynamics::Recording rec = record_square([&](double t, double w) {
    call_t.push_back(t);
    call_w.push_back(w);
    return curve(t);
  });
  std::vector<double> want_t, want_w;
  for (const double t : rec.find("time_s")->values)
    if (!at_a_step_end(t)) {
      want_t.push_back(t);
      want_w.push_back(std::fmod(t, kSlowStep) / kSlowStep);
    }
  ASSERT_EQ(want_t.size(), 3u * kSlowSteps);
  EXPECT_EQ(call_t, want_t);
  EXPECT_EQ(call_w, want_w);
}

// A sample whose time differs from the step's end by round-off only (0.3 against 0.1 + 0.2 =
// 0.30000000000000004, w = 1 − 2e-16) is at the end (w ≥ 1 − 1e-9): it gets the end's value and
// `inside` is not called for it; the sample at 0.15 (w = 1/2) is inside and is called for, its
// value the marker `inside` returns.
TEST(ChannelRecorder, ASampleWithinRoundOffOfAStepsEndIsAtTheEnd) {
  dynamics::Recording rec;
  CurveRecorder recorder(rec,
                         {CurveRecorder::sampled(dynamics::signal_names::kTime, "s", [](double t) { return t; }),
                          CurveRecorder::refined("square_refined", "s2", [](const Curve& c) { return c.square; })});
  recorder.sample(0.0);
  recorder.start(curve(0.0));
  recorder.sample(0.15);
  recorder.sample(0.3);
  const double tb = 0.1 + 0.2;
  ASSERT_LT(0.3, tb);  // the premise: the sample is (by round-off) before the step's end
  std::vector<double> called;
  recorder.step(curve(tb), 0.0, tb, [&](double t, double) {
    called.push_back(t);
    return Curve{t, -1.0};  // a marker: a sample read from `inside` records -1
  });
  EXPECT_EQ(called, (std::vector<double>{0.15}));
  const auto& x = rec.find("square_refined")->values;
  ASSERT_EQ(x.size(), 3u);
  EXPECT_EQ(x[0], 0.0);
  EXPECT_EQ(x[1], -1.0);
  // The end's value up to the interpolation's round-off (w = 1 − 2e-16): tolerance 1e-15 relative.
  EXPECT_NEAR(x[2], tb * tb, 1e-15 * tb * tb);
}

// Without `inside`, a refined channel is interpolated exactly as an interpolated one (the same
// arithmetic, so compared with ==); the chord's gap from t² inside the steps (asserted) keeps
// this from passing by both being t².
TEST(ChannelRecorder, WithoutInsideARefinedChannelIsInterpolatedLikeAnInterpolatedOne) {
  const dynamics::Recording rec = record_square({});
  const auto& t = rec.find("time_s")->values;
  const auto& lin = rec.find("square_interpolated")->values;
  const auto& fine = rec.find("square_refined")->values;
  ASSERT_EQ(t.size(), 17u);
  EXPECT_EQ(fine, lin);
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(fine[k], chord_of_square(t[k]), 1e-14 * (1 + t[k] * t[k])) << "t = " << t[k];
    if (!at_a_step_end(t[k])) {
      EXPECT_GT(fine[k] - t[k] * t[k], 0.04) << "t = " << t[k];
    }
  }
}

TEST(ChannelRecorder, TheFirstChannelMustBeTheSampledTime) {
  dynamics::Recording rec;
  EXPECT_THROW(Recorder(rec, {Recorder::interpolated("ramp", "1", [](const SlowState& s) { return s.ramp; })}),
               std::logic_error);
  EXPECT_THROW(Recorder(rec, {Recorder::interpolated("time_s", "s", [](const SlowState& s) { return s.t_s; })}),
               std::logic_error);
}

}  // namespace
}  // namespace shudder::components
