// ThermalStepPlan (rig_models/thermal_step_plan.hpp): BDF2's steps end on the drive cycle's
// breakpoints, cut each segment into equal steps no longer than the nominal one, and grow by at
// most 2x after a short step (variable-step BDF2 is zero-stable only for ratios < 1 + √2).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "rig_models/thermal_step_plan.hpp"

namespace shudder::rig_models {
namespace {

// The step ends from 0 to end_s, as the runner walks them (t += dt, until within 1e-12 of the end).
std::vector<double> walk(const ThermalStepPlan& plan, double end_s) {
  std::vector<double> ends;
  double t = 0.0, previous = 0.0;
  while (t < end_s - 1e-12 && ends.size() < 100000) {
    const double dt = plan.next_step_s(t, previous);
    EXPECT_GT(dt, 0.0);
    if (previous > 0.0) {
      EXPECT_LE(dt, 2.0 * previous * (1.0 + 1e-12)) << "at t = " << t;
    }
    previous = dt;
    t += dt;
    ends.push_back(t);
  }
  return ends;
}

bool has_end_at(const std::vector<double>& ends, double t) {
  for (double e : ends)
    if (std::abs(e - t) < 1e-12) return true;
  return false;
}

// Knots on the step grid (Paper G Case 1: 0 and 10 s, 40 ms): the plain grid, 250 steps of
// exactly the nominal length but the last, which lands on the end.
TEST(ThermalStepPlan, KnotsOnTheGridKeepTheNominalSteps) {
  const ThermalStepPlan plan({0.0, 10.0, 0.0}, 0.04, 10.0);
  const auto ends = walk(plan, 10.0);
  ASSERT_EQ(ends.size(), 250u);
  double t = 0.0, previous = 0.0;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const double dt = plan.next_step_s(t, previous);
    EXPECT_EQ(dt, 0.04) << k;
    previous = dt;
    t += dt;
  }
  EXPECT_NEAR(ends.back(), 10.0, 1e-12);
}

// Knots off the grid (a 5 ms ramp from 1.0 s, a 2 ms one from 3.0 s): a step ends on each knot,
// the 5 ms segment is one step, and the steps after it double (10, 20 ms) until the rest of the
// segment, 1.035 → 3.0 s, is cut into 50 equal steps of 39.3 ms; no step is longer than 40 ms.
TEST(ThermalStepPlan, StepsEndOnEveryKnotAndGrowAtMostTwofold) {
  const ThermalStepPlan plan({0.0, 1.0, 1.005, 3.0, 3.002, 6.0}, 0.04, 6.0);
  const auto ends = walk(plan, 6.0);
  for (double knot : {1.0, 1.005, 3.0, 3.002, 6.0}) EXPECT_TRUE(has_end_at(ends, knot)) << knot;
  double t = 0.0, previous = 0.0, longest = 0.0;
  std::vector<double> after_ramp;
  while (t < 6.0 - 1e-12) {
    const double dt = plan.next_step_s(t, previous);
    longest = std::max(longest, dt);
    if (t > 1.0 + 1e-9 && after_ramp.size() < 4) after_ramp.push_back(dt);
    previous = dt;
    t += dt;
  }
  EXPECT_LE(longest, 0.04 * (1.0 + 1e-12));
  ASSERT_EQ(after_ramp.size(), 4u);
  EXPECT_NEAR(after_ramp[0], 0.010, 1e-12);  // 2 x the 5 ms ramp step
  EXPECT_NEAR(after_ramp[1], 0.020, 1e-12);
  EXPECT_LE(after_ramp[2], 0.04 + 1e-12);
  EXPECT_GT(after_ramp[2], 0.03);  // back near the nominal step: (3.0 − 1.035) / 50 = 39.3 ms
}

// A knot within round-off of a grid point leaves no sliver of a step; knots outside (0, end)
// and repeated knots change nothing.
TEST(ThermalStepPlan, NoSliversAndKnotsOutsideTheRunIgnored) {
  const ThermalStepPlan plain({}, 0.01, 1.0);
  const ThermalStepPlan noisy({-1.0, 0.0, 0.5 + 1e-14, 0.5, 0.5, 1.0, 2.0}, 0.01, 1.0);
  const auto a = walk(plain, 1.0), b = walk(noisy, 1.0);
  ASSERT_EQ(a.size(), 100u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-12) << k;
}

TEST(ThermalStepPlan, RefusesAStepOrDurationNotAboveZero) {
  EXPECT_THROW(ThermalStepPlan({}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(ThermalStepPlan({}, 0.01, 0.0), std::invalid_argument);
  EXPECT_THROW(ThermalStepPlan({}, std::nan(""), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace shudder::rig_models
