// The table friction law (clutch/table_friction.hpp) against its definition: grid values
// exactly at grid points, linear in ln(v) between speeds, bilinear in (T, F) of the values,
// held beyond every axis, and dmu/dv the derivative of mu.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "clutch/table_friction.hpp"

namespace {

using shudder::clutch::TableFriction;

// mu = 0.10 + 0.01 ln(v/5) − 2e-4 (T − 20) − 1e-6 (F − 10000): every interpolation rule is
// exact on it (linear in ln v, T and F), so any value between grid points has a closed form.
double exact(double v, double t, double f) {
  return 0.10 + 0.01 * std::log(v / 5.0) - 2e-4 * (t - 20.0) - 1e-6 * (f - 10000.0);
}

TableFriction make() {
  const std::vector<double> v{5.0, 50.0, 500.0}, t{20.0, 80.0}, f{10000.0, 20000.0};
  std::vector<double> mu;
  for (double ti : t)
    for (double fi : f)
      for (double vi : v) mu.push_back(exact(vi, ti, fi));
  return TableFriction(v, t, f, mu);
}

TEST(TableFriction, InterpolatesLogLinearInSpeedAndBilinearInTemperatureAndLoad) {
  const TableFriction law = make();
  for (double v : {5.0, 12.0, 50.0, 170.0, 500.0})
    for (double t : {20.0, 33.0, 80.0})
      for (double f : {10000.0, 14000.0, 20000.0}) EXPECT_NEAR(law.mu(v, t, f), exact(v, t, f), 1e-12);
}

TEST(TableFriction, HoldsItsEdgesAndHasZeroSlopeBeyondTheSpeedAxis) {
  const TableFriction law = make();
  EXPECT_NEAR(law.mu(1.0, 0.0, 5000.0), exact(5.0, 20.0, 10000.0), 1e-12);
  EXPECT_NEAR(law.mu(900.0, 120.0, 30000.0), exact(500.0, 80.0, 20000.0), 1e-12);
  EXPECT_EQ(law.dmu_dv_per_mm_s(1.0, 40.0, 15000.0), 0.0);
  EXPECT_EQ(law.dmu_dv_per_mm_s(900.0, 40.0, 15000.0), 0.0);
  EXPECT_EQ(law.temp_range_C().first, 20.0);
  EXPECT_EQ(law.max_speed_mm_s(), 500.0);
}

TEST(TableFriction, SlopeIsTheDerivativeOfMu) {
  const TableFriction law = make();
  for (double v : {7.0, 30.0, 260.0}) {
    // d/dv of 0.01 ln v = 0.01 / v, exactly.
    EXPECT_NEAR(law.dmu_dv_per_mm_s(v, 50.0, 15000.0), 0.01 / v, 1e-12);
  }
}

TEST(TableFriction, RejectsMalformedGrids) {
  EXPECT_THROW(TableFriction({5.0, 5.0}, {20.0}, {1e4}, {0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(TableFriction({0.0, 5.0}, {20.0}, {1e4}, {0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(TableFriction({5.0, 50.0}, {20.0}, {1e4}, {0.1}), std::invalid_argument);
  EXPECT_THROW(TableFriction({5.0, 50.0}, {20.0}, {1e4}, {0.1, NAN}), std::invalid_argument);
}

}  // namespace
