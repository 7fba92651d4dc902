// Walther / ASTM D341 viscosity against the values worked out in docs/physics.md §3 for fluid C
// (nu40 = 35 cSt, nu100 = 6.7 cSt): A ≈ 8.4504, B ≈ 3.3093; ≈ 85 cSt at 20 °C, 10.3 cSt at
// 80 °C, 4.7 cSt at 120 °C (quoted to 2–3 digits, hence the tolerances).
#include <gtest/gtest.h>

#include "clutch/fluid.hpp"

using shudder::clutch::WaltherViscosity;

TEST(WaltherViscosity, PassesThroughItsTwoDefiningPoints) {
  const WaltherViscosity w(35.0, 6.7);
  EXPECT_NEAR(w.kinematic_cSt(40.0), 35.0, 1e-9);
  EXPECT_NEAR(w.kinematic_cSt(100.0), 6.7, 1e-9);
}

TEST(WaltherViscosity, FluidCConstantsAndValuesMatchPhysicsDigest) {
  const WaltherViscosity w(35.0, 6.7);
  EXPECT_NEAR(w.a(), 8.4504, 5e-4);  // quoted to 4 decimals
  EXPECT_NEAR(w.b(), 3.3093, 5e-4);
  EXPECT_NEAR(w.kinematic_cSt(20.0), 85.0, 1.0);   // quoted as "≈ 85"
  EXPECT_NEAR(w.kinematic_cSt(80.0), 10.3, 0.05);  // quoted to 0.1
  EXPECT_NEAR(w.kinematic_cSt(120.0), 4.7, 0.05);
}

TEST(WaltherViscosity, RejectsInvertedOrNonPositiveViscosities) {
  EXPECT_THROW(WaltherViscosity(6.7, 35.0), std::invalid_argument);
  EXPECT_THROW(WaltherViscosity(35.0, 0.0), std::invalid_argument);
}
