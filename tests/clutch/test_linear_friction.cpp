// Linear friction–temperature law (Papers B, C, E): mu_k(T) = alpha_k*T + beta_k at speed v_k,
// linear in ln(v) between tabulated speeds, held at the end values outside them.
//
// Fixture: Paper E fluid A at 20 kN, speeds 1 rpm = 4.82 mm/s and 50 rpm = 241 mm/s:
//   mu1(T)  = -5.42e-4*T + 0.1018       mu50(T) = -2.96e-4*T + 0.1164
// At T = 30 °C: mu1 = 0.1018 - 0.01626 = 0.08554, mu50 = 0.1164 - 0.00888 = 0.10752.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "clutch/linear_friction.hpp"

namespace {

using shudder::clutch::LinearTemperatureFriction;
using shudder::clutch::LinearTemperaturePoint;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kV1 = 4.82, kV50 = 241.0;

LinearTemperatureFriction fluid_a() {
  return LinearTemperatureFriction({{kV1, -5.42e-4, 0.1018}, {kV50, -2.96e-4, 0.1164}});
}

// Hand values are exact to a few ulp of the decimal arithmetic: tolerance 1e-14.
constexpr double kTol = 1e-14;

TEST(LinearTemperatureFriction, ReproducesTheLinesAtTabulatedSpeeds) {
  const auto law = fluid_a();
  EXPECT_NEAR(law.mu(kV1, 30.0, 20000.0), 0.08554, kTol);
  EXPECT_NEAR(law.mu(kV50, 30.0, 20000.0), 0.10752, kTol);
  EXPECT_NEAR(law.mu(kV1, 0.0, 20000.0), 0.1018, kTol);  // beta is mu at 0 °C
  EXPECT_EQ(law.min_speed_mm_s(), kV1);
}

TEST(LinearTemperatureFriction, InterpolatesLinearlyInLogSpeed) {
  const auto law = fluid_a();
  // Geometric mean sqrt(4.82*241) = 34.0825 mm/s lies half way in ln(v):
  //   mu = (0.08554 + 0.10752)/2 = 0.09653 at 30 °C.
  EXPECT_NEAR(law.mu(std::sqrt(kV1 * kV50), 30.0, 20000.0), 0.09653, kTol);
  // A quarter of the way: v = 4.82 * 50^0.25 -> mu = 0.75*0.08554 + 0.25*0.10752 = 0.091035.
  EXPECT_NEAR(law.mu(kV1 * std::pow(50.0, 0.25), 30.0, 20000.0), 0.091035, kTol);
}

TEST(LinearTemperatureFriction, HoldsEndValuesOutsideTheTabulatedSpeedsWithZeroSlope) {
  const auto law = fluid_a();
  for (double v : {0.0, 1.0, 4.8}) {
    EXPECT_EQ(law.mu(v, 30.0, 20000.0), law.mu(kV1, 30.0, 20000.0)) << v;
    EXPECT_EQ(law.dmu_dv_per_mm_s(v, 30.0, 20000.0), 0.0) << v;
  }
  for (double v : {241.01, 1000.0}) {
    EXPECT_EQ(law.mu(v, 30.0, 20000.0), law.mu(kV50, 30.0, 20000.0)) << v;
    EXPECT_EQ(law.dmu_dv_per_mm_s(v, 30.0, 20000.0), 0.0) << v;
  }
  // The sliding direction does not matter, and the lines do not depend on load.
  EXPECT_EQ(law.mu(-100.0, 30.0, 20000.0), law.mu(100.0, 30.0, 20000.0));
  EXPECT_EQ(law.mu(100.0, 30.0, 5000.0), law.mu(100.0, 30.0, 30000.0));
}

TEST(LinearTemperatureFriction, SlopeMatchesHandValueAndCentralDifference) {
  const auto law = fluid_a();
  // dmu/dv = (mu50 - mu1) / (v * ln(241/4.82)) = 0.02198 / (v * ln 50), ln 50 = 3.9120230;
  // at v = 34.082547 (geometric mean): 0.02198 / 133.33167 = 1.6485201e-4 per mm/s.
  const double vm = std::sqrt(kV1 * kV50);
  EXPECT_NEAR(law.dmu_dv_per_mm_s(vm, 30.0, 20000.0), 1.6485201e-4, 1e-11);  // 8 digits
  // Central difference, h = 1e-4*v: truncation ~ h²/6 * |mu'''| is < 1e-8 relative.
  for (double v : {6.0, 20.0, 100.0, 200.0}) {
    for (double t : {-20.0, 30.0, 90.0}) {
      const double h = 1e-4 * v;
      const double fd = (law.mu(v + h, t, 2e4) - law.mu(v - h, t, 2e4)) / (2.0 * h);
      EXPECT_NEAR(law.dmu_dv_per_mm_s(v, t, 2e4), fd, 1e-7 * std::abs(fd)) << v << " " << t;
    }
  }
}

TEST(LinearTemperatureFriction, ConstructorRejectsBadSpeedsAndValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using P = LinearTemperaturePoint;
  EXPECT_THAT([] { LinearTemperatureFriction(std::vector<P>{}); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("at least one speed")));
  EXPECT_THAT(
      [] {
        LinearTemperatureFriction({{241.0, 0, 0.1}, {4.82, 0, 0.1}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("strictly increasing")));
  EXPECT_THAT(
      [] {
        LinearTemperatureFriction({{0.0, 0, 0.1}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("speeds must be > 0")));
  EXPECT_THAT(
      [nan] {
        LinearTemperatureFriction({{4.82, nan, 0.1}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("non-finite")));
}

}  // namespace
