// Mäki boundary-friction model (Paper G eq. 13), v in mm/s:
//
//     mu(v)  = C1*tanh(C2*v) + C3*v^0.1 + C4
//     dmu/dv = C1*C2*(1 - tanh²(C2*v)) + 0.1*C3*v^-0.9
//
// checked against hand-computed values, a central finite difference, the Paper G range rules
// (speed [6, 590] mm/s, load [10, 25] kN, temperature [-40, 200] °C held at the edges), the
// bilinear interpolation of mu VALUES, the shift rule for rows outside -20..90 °C, and the
// constructor's validation.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "clutch/maki_friction.hpp"

namespace {

using shudder::clutch::MakiFrictionMatrix;
using shudder::clutch::MakiSet;
using shudder::clutch::shifted_row;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// Paper G Table 2, 70 °C / 20 kN.
constexpr MakiSet kSet70C20kN{-0.039, 0.001, 0.077, -0.024};

// A matrix of one set: only the speed rules act.
MakiFrictionMatrix single(const MakiSet& s) { return MakiFrictionMatrix({20000.0}, {70.0}, {s}); }

TEST(MakiSet, SeventyDegreeTwentyKiloNewtonSetMatchesHandValues) {
  // v = 4.82 mm/s (1 rpm at r = 46 mm):
  //   tanh(0.00482) = 0.00482 - 0.00482³/3 = 0.0048199627   -> C1*tanh = -0.00018797854
  //   4.82^0.1 = exp(0.1*ln 4.82) = exp(0.15727739) = 1.1703202 -> C3*... = 0.09011466
  //   mu = -0.00018798 + 0.09011466 - 0.024 = 0.06592668            (docs/physics.md §1: "0.066")
  // v = 241 mm/s (50 rpm):
  //   tanh(0.241) = 0.2364401 -> -0.00922116;  241^0.1 = exp(0.54847969) = 1.7306199 -> 0.13325774
  //   mu = -0.00922116 + 0.13325774 - 0.024 = 0.10003658           (docs/physics.md §1: "0.100")
  // Tolerance 1e-8: the hand values are rounded to 8 decimals.
  EXPECT_NEAR(kSet70C20kN.mu(4.82), 0.06592668, 1e-8);
  EXPECT_NEAR(kSet70C20kN.mu(241.0), 0.10003658, 1e-8);
  // dmu/dv at 241 mm/s: C1*C2*(1 - 0.2364401²) = -3.9e-5 * 0.9440961 = -3.6819748e-5,
  //   0.1*C3*241^-0.9 = 0.0077 * 0.0071809956 = 5.5293666e-5;  sum = 1.8473918e-5 per mm/s.
  EXPECT_NEAR(kSet70C20kN.dmu_dv(241.0), 1.8473918e-5, 1e-12);  // hand value to 8 digits
}

TEST(MakiSet, AnalyticSlopeMatchesCentralDifference) {
  // Central difference error ~ h²/6 * |mu'''|; with h = 1e-4*v it is < 1e-10 of the slope at
  // these speeds, and round-off ~ eps*mu/h < 1e-11: tolerance 1e-7 relative.
  for (const MakiSet& s :
       {kSet70C20kN, MakiSet{-0.338, 0.0001, 0.077, -0.025}, MakiSet{-0.0025, 0.013, 0.012, 0.098}}) {
    for (double v : {6.0, 20.0, 100.0, 241.0, 590.0}) {
      const double h = 1e-4 * v;
      const double fd = (s.mu(v + h) - s.mu(v - h)) / (2.0 * h);
      EXPECT_NEAR(s.dmu_dv(v), fd, 1e-7 * std::abs(fd) + 1e-13) << "v = " << v;
    }
  }
}

TEST(MakiFrictionMatrix, SpeedIsClampedToSixAndFiveHundredNinetyMillimetresPerSecond) {
  const auto m = single(kSet70C20kN);
  EXPECT_EQ(m.min_speed_mm_s(), 6.0);
  EXPECT_EQ(m.max_speed_mm_s(), 590.0);
  // Below 6 mm/s (incl. standstill and the 1-rpm speed 4.82) mu is held at mu(6); the slope is 0.
  for (double v : {0.0, 1.0, 4.82, 5.999}) {
    EXPECT_EQ(m.mu(v, 70.0, 20000.0), kSet70C20kN.mu(6.0)) << v;
    EXPECT_EQ(m.dmu_dv_per_mm_s(v, 70.0, 20000.0), 0.0) << v;
  }
  // Above 590 mm/s mu is held at mu(590); the slope is 0.
  for (double v : {590.001, 1000.0}) {
    EXPECT_EQ(m.mu(v, 70.0, 20000.0), kSet70C20kN.mu(590.0)) << v;
    EXPECT_EQ(m.dmu_dv_per_mm_s(v, 70.0, 20000.0), 0.0) << v;
  }
  // Inside, the set's own value and slope; the sign of v (sliding direction) does not matter.
  EXPECT_EQ(m.mu(241.0, 70.0, 20000.0), kSet70C20kN.mu(241.0));
  EXPECT_EQ(m.mu(-241.0, 70.0, 20000.0), kSet70C20kN.mu(241.0));
  EXPECT_EQ(m.dmu_dv_per_mm_s(100.0, 70.0, 20000.0), kSet70C20kN.dmu_dv(100.0));
}

// Constant sets (C1 = C2 = 0) make mu = C3*v^0.1 + C4, so bilinear blends are checked by hand:
//
//          10 kN                 20 kN
//   0 °C   C3 = 0.01, C4 = 0.10  C3 = 0.02, C4 = 0.12
// 100 °C   C3 = 0.03, C4 = 0.06  C3 = 0.04, C4 = 0.09
MakiFrictionMatrix two_by_two() {
  return MakiFrictionMatrix({10000.0, 20000.0}, {0.0, 100.0},
                            {{0, 0, 0.01, 0.10}, {0, 0, 0.02, 0.12}, {0, 0, 0.03, 0.06}, {0, 0, 0.04, 0.09}});
}

TEST(MakiFrictionMatrix, BilinearBetweenTwoLoadsAndTwoTemperatures) {
  const auto m = two_by_two();
  // F = 12.5 kN -> w_load = 0.25; T = 40 °C -> w_temp = 0.4.
  //   C4: lo = 0.75*0.10 + 0.25*0.12 = 0.105, hi = 0.75*0.06 + 0.25*0.09 = 0.0675,
  //       0.6*0.105 + 0.4*0.0675 = 0.090
  //   C3: lo = 0.0125, hi = 0.0325, blend = 0.0205
  //   mu(100) = 0.090 + 0.0205 * 100^0.1 = 0.090 + 0.0205*1.5848932 = 0.12249031
  //   dmu/dv(100) = 0.1 * 0.0205 * 100^-0.9 = 0.00205 * 0.015848932 = 3.2490311e-5
  // Tolerances: hand values rounded to 8 significant digits.
  EXPECT_NEAR(m.mu(100.0, 40.0, 12500.0), 0.12249031, 1e-8);
  EXPECT_NEAR(m.dmu_dv_per_mm_s(100.0, 40.0, 12500.0), 3.2490311e-5, 1e-12);
  // At a grid point the blend is that set alone (weights exactly 0/1).
  EXPECT_DOUBLE_EQ(m.mu(100.0, 100.0, 10000.0), 0.03 * std::pow(100.0, 0.1) + 0.06);
}

TEST(MakiFrictionMatrix, LoadIsClampedToTheMatrixEnds) {
  const auto m = two_by_two();
  for (double t : {0.0, 37.0, 100.0}) {
    EXPECT_EQ(m.mu(50.0, t, 5000.0), m.mu(50.0, t, 10000.0)) << t;
    EXPECT_EQ(m.mu(50.0, t, 0.0), m.mu(50.0, t, 10000.0)) << t;
    EXPECT_EQ(m.mu(50.0, t, 40000.0), m.mu(50.0, t, 20000.0)) << t;
    EXPECT_EQ(m.dmu_dv_per_mm_s(50.0, t, 40000.0), m.dmu_dv_per_mm_s(50.0, t, 20000.0)) << t;
  }
}

TEST(MakiFrictionMatrix, TemperatureIsHeldAtTheEndRowsOutsideMinusFortyToTwoHundred) {
  // Paper G's matrix ends: -40 °C and 200 °C, with different levels at each end.
  const MakiFrictionMatrix m({10000.0, 25000.0}, {-40.0, 200.0},
                             {{0, 0, 0.0, 0.12}, {0, 0, 0.0, 0.13}, {0, 0, 0.0, 0.05}, {0, 0, 0.0, 0.06}});
  for (double f : {10000.0, 17500.0, 25000.0}) {
    EXPECT_EQ(m.mu(100.0, -50.0, f), m.mu(100.0, -40.0, f)) << f;
    EXPECT_EQ(m.mu(100.0, -273.0, f), m.mu(100.0, -40.0, f)) << f;
    EXPECT_EQ(m.mu(100.0, 250.0, f), m.mu(100.0, 200.0, f)) << f;
  }
  // Between the rows it is linear in T: at 80 °C, w = 120/240 = 0.5, 10 kN: (0.12+0.05)/2.
  EXPECT_NEAR(m.mu(100.0, 80.0, 10000.0), 0.085, 1e-15);  // exact up to rounding of the weights
}

TEST(MakiFrictionMatrix, InterpolatesMuValuesNotCoefficients) {
  // One load, rows at 0 and 100 °C differing only in C2 (C1 = 0.1, C3 = C4 = 0):
  //   A: C2 = 0.001 -> mu_A(100) = 0.1*tanh(0.1) = 0.1*0.099667995 = 0.0099667995
  //   B: C2 = 0.1   -> mu_B(100) = 0.1*tanh(10)  = 0.1*0.99999999588 = 0.099999999588
  // At 50 °C, value interpolation: (mu_A + mu_B)/2 = 0.054983399
  // Coefficient interpolation would give 0.1*tanh(0.0505*100) = 0.1*tanh(5.05) = 0.099991795,
  // almost twice as large, so the two are told apart by far more than the tolerance (1e-9,
  // the rounding of the hand value).
  const MakiFrictionMatrix m({20000.0}, {0.0, 100.0}, {{0.1, 0.001, 0.0, 0.0}, {0.1, 0.1, 0.0, 0.0}});
  EXPECT_NEAR(m.mu(100.0, 50.0, 20000.0), 0.054983399, 1e-9);
  const MakiSet coefficient_blend{0.1, 0.0505, 0.0, 0.0};
  EXPECT_GT(std::abs(m.mu(100.0, 50.0, 20000.0) - coefficient_blend.mu(100.0)), 0.04);
}

TEST(ShiftedRow, KeepsTheShapeAndShiftsC4ByTwoPointOneE4PerDegree) {
  // Above 90 °C friction falls: at 200 °C, C4 = -0.024 - 2.1e-4*(200 - 90) = -0.024 - 0.0231.
  const MakiSet hot = shifted_row(kSet70C20kN, 90.0, 200.0);
  EXPECT_EQ(hot.c1, kSet70C20kN.c1);
  EXPECT_EQ(hot.c2, kSet70C20kN.c2);
  EXPECT_EQ(hot.c3, kSet70C20kN.c3);
  EXPECT_NEAR(hot.c4, -0.0471, 1e-15);  // one rounding in the product
  // Below -20 °C friction rises: at -40 °C, C4 = -0.024 + 2.1e-4*20 = -0.0198.
  EXPECT_NEAR(shifted_row(kSet70C20kN, -20.0, -40.0).c4, -0.0198, 1e-15);
  // So mu shifts by the same amount at every speed.
  EXPECT_NEAR(kSet70C20kN.mu(100.0) - hot.mu(100.0), 0.0231, 1e-15);
  // Another slope when given.
  EXPECT_NEAR(shifted_row(kSet70C20kN, 90.0, 100.0, 1e-3).c4, -0.034, 1e-15);
}

TEST(MakiFrictionMatrix, ConstructorRejectsBadAxesAndSizes) {
  const MakiSet s = kSet70C20kN;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { MakiFrictionMatrix({}, {70.0}, {}); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("loads must not be empty")));
  EXPECT_THAT(
      [&] {
        MakiFrictionMatrix({20000.0, 10000.0}, {70.0}, {s, s});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("loads must be strictly increasing")));
  EXPECT_THAT(
      [&] {
        MakiFrictionMatrix({10000.0}, {70.0, 70.0}, {s, s});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("temperatures must be strictly increasing")));
  EXPECT_THAT([&] { MakiFrictionMatrix({10000.0}, {nan}, {s}); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("non-finite value")));
  EXPECT_THAT(
      [&] {
        MakiFrictionMatrix({10000.0, 20000.0}, {70.0}, {s});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("has 1 parameter sets")));
  EXPECT_THAT(
      [&] {
        MakiFrictionMatrix({10000.0}, {70.0}, {MakiSet{nan, 0, 0, 0}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("non-finite coefficient")));
  EXPECT_THAT([&] { MakiFrictionMatrix({10000.0}, {70.0}, {s}, 0.0, 590.0); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("0 < min < max")));
  EXPECT_THAT([&] { MakiFrictionMatrix({10000.0}, {70.0}, {s}, 600.0, 590.0); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("0 < min < max")));
}

}  // namespace

namespace {

// The definition, written out: the bilinear blend of the four surrounding sets' mu values.
double blend_of_set_values(const MakiFrictionMatrix& m, double v_mm_s, double temp_C, double load_N) {
  const auto bracket = [](const std::vector<double>& axis, double x) -> std::pair<std::size_t, double> {
    if (axis.size() == 1 || x <= axis.front()) return {0, 0.0};
    if (x >= axis.back()) return {axis.size() - 2, 1.0};
    std::size_t i = 0;
    while (axis[i + 1] <= x) ++i;
    return {i, (x - axis[i]) / (axis[i + 1] - axis[i])};
  };
  const double v = std::clamp(std::abs(v_mm_s), m.min_speed_mm_s(), m.max_speed_mm_s());
  const auto [it, wt] = bracket(m.temps_C(), temp_C);
  const auto [il, wl] = bracket(m.loads_N(), load_N);
  const std::size_t it1 = std::min(it + 1, m.temps_C().size() - 1);
  const std::size_t il1 = std::min(il + 1, m.loads_N().size() - 1);
  const double lo = (1.0 - wl) * m.set(it, il).mu(v) + wl * m.set(it, il1).mu(v);
  const double hi = (1.0 - wl) * m.set(it1, il).mu(v) + wl * m.set(it1, il1).mu(v);
  return (1.0 - wt) * lo + wt * hi;
}

}  // namespace

// Three loads by four temperatures of distinct sets (equal and unequal C2 among neighbours),
// shared by the bit-for-bit tests below.
MakiFrictionMatrix three_loads_four_temps() {
  return MakiFrictionMatrix({10000.0, 15000.0, 25000.0}, {-40.0, 20.0, 70.0, 200.0},
                            {{-0.031, 0.0014, 0.057, 0.035},
                             {-0.026, 0.0037, 0.035, 0.07},
                             {-0.0024, 0.0098, 0.012, 0.101},
                             {-0.024, 0.0024, 0.047, 0.05},
                             {-0.024, 0.0024, 0.020, 0.084},
                             {-0.038, 0.002, 0.037, 0.068},
                             {-0.039, 0.001, 0.077, -0.024},
                             {-0.039, 0.001, 0.05, 0.01},
                             {-0.038, 0.002, 0.03, 0.02},
                             {-0.031, 0.0014, 0.057, 0.035},
                             {-0.026, 0.0037, 0.035, 0.07},
                             {-0.0024, 0.0098, 0.012, 0.101}});
}

// mu() shares v^0.1 and equal-rate tanh terms between the sets and skips sets of weight zero;
// that must give the definition's numbers bit for bit (the thermal runs' results rely on it),
// inside the matrix, on its axes, clamped beyond them, and with equal and unequal C2.
TEST(MakiFrictionMatrix, FastBlendEqualsTheBlendOfSetValuesBitForBit) {
  const MakiFrictionMatrix m = three_loads_four_temps();
  int checked = 0;
  for (double v : {0.0, 3.0, 6.0, 17.3, 241.0, 590.0, 900.0, -55.0})
    for (double t : {-60.0, -40.0, 0.0, 20.0, 45.5, 70.0, 133.3, 200.0, 250.0})
      for (double f : {0.0, 10000.0, 12345.0, 15000.0, 21000.0, 25000.0, 25300.0}) {
        EXPECT_EQ(m.mu(v, t, f), blend_of_set_values(m, v, t, f)) << v << " " << t << " " << f;
        ++checked;
      }
  EXPECT_EQ(checked, 8 * 9 * 7);
}

// mu_at_load() keeps v^0.1 and tanh(C2 v) per speed between calls at the same speeds; every
// call must still give mu()'s numbers bit for bit: the same speeds with new temperatures (the
// cached terms reused), new speeds (the cache renewed, including its length), clamped speeds,
// and points whose four sets have other C2 than the previous call's (tanh taken on first use).
TEST(MakiFrictionMatrix, BatchAtOneLoadEqualsPointwiseMuBitForBitWhileSpeedsRepeat) {
  const MakiFrictionMatrix m = three_loads_four_temps();
  const shudder::clutch::FrictionLaw& law = m;
  shudder::clutch::SpeedTerms terms;
  const std::vector<std::vector<double>> speed_sets{{3.0, 17.3, 241.0, 590.0, 900.0},
                                                    {3.0, 17.3, 241.0, 590.0, 900.0},
                                                    {-55.0, 6.0, 100.0},
                                                    {-55.0, 6.0, 100.0},
                                                    {0.0, 6.0, 100.0, 300.0, 1e4, 42.0}};
  const std::vector<std::vector<double>> temp_sets{{-60.0, 20.0, 45.5, 133.3, 250.0},
                                                   {200.0, 70.0, 0.0, -40.0, 21.0},
                                                   {45.5, 133.3, -10.0},
                                                   {-40.0, 199.0, 70.0},
                                                   {20.0, 20.0, 75.0, 150.0, -45.0, 69.0}};
  int checked = 0;
  for (double load : {12345.0, 25300.0, 10000.0})
    for (std::size_t c = 0; c < speed_sets.size(); ++c) {
      std::vector<double> out(speed_sets[c].size());
      law.mu_at_load(speed_sets[c], temp_sets[c], load, out, terms);
      for (std::size_t i = 0; i < out.size(); ++i, ++checked)
        EXPECT_EQ(out[i], m.mu(speed_sets[c][i], temp_sets[c][i], load)) << "call " << c << ", point " << i;
    }
  EXPECT_EQ(checked, 3 * 22);
}
