// The multi-rate loop's restarts at input breaks (components/multirate_clutch.hpp): every break
// is delivered to `at_break` exactly once. A sampled controller's instants k·T_c fall on the
// thermal steps' ends, which are moved onto the sample times (k/rate) when round-off is all that
// separates them; 35 × 0.01 = 0.35000000000000003 lies 5.6e-17 s after the step's end
// 0.34999999999999998. Such a break is taken at that end, and must not come again as a break of
// the next step (it did: the Haldex control unit then read a second, zero-length period, a mean
// speed of 0, into its filter 35 times in 3 s).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "components/multirate_clutch.hpp"

namespace shudder::components {
namespace {

TEST(MultirateBreaks, EachBreakIsTakenOnceAtItsTime) {
  dynamics::TorsionalNetwork net;
  net.add_inertia({"body", 1.0});
  net.add_shaft({"spring", 0, dynamics::kGround, 100.0, 1.0});
  net.validate();
  dynamics::Simulation sim(net);
  sim.initialize(0.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 1.0), Eigen::VectorXd());
  const double period_s = 0.01, duration_s = 3.0;
  std::vector<double> breaks;
  for (long k = 1; static_cast<double>(k) * period_s < duration_s - 1e-12; ++k)
    breaks.push_back(static_cast<double>(k) * period_s);
  std::vector<double> taken;
  run_multirate(
      sim, {}, duration_s, period_s, 1000.0, [](const dynamics::Sample&) {}, [](const SlowStep&) {}, breaks,
      [&](double t) { taken.push_back(t); });
  ASSERT_EQ(taken.size(), breaks.size());
  for (std::size_t i = 0; i < breaks.size(); ++i) EXPECT_NEAR(taken[i], breaks[i], 1e-12) << i;
}

}  // namespace
}  // namespace shudder::components
