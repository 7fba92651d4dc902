// Friction outside its data (clutch/friction_data_range, components/friction_range_block):
// the tally against hand-counted steps, and a prescribed-slip run at 5 kN (below fluid C's
// 10 kN first load) that says so for its whole duration, once, in its block.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "clutch/friction_data_range.hpp"
#include "clutch/maki_friction.hpp"
#include "io/fluid_loader.hpp"
#include "components/friction_range_block.hpp"
#include "tests/support/ramp_runs.hpp"

namespace {

using namespace shudder;

TEST(FrictionDataRange, CountsEachRangeAndEachStepOnce) {
  const clutch::MakiSet s{-0.039, 0.001, 0.077, -0.024};
  const clutch::MakiFrictionMatrix law({10000.0, 25000.0}, {-20.0, 90.0}, {s, s, s, s}, 6.0, 590.0);
  clutch::FrictionDataRange r(law);
  Eigen::VectorXd radius(2), temp(2);
  radius << 0.04, 0.05;
  temp << 50.0, 60.0;
  r.add(1.0, 1.0, radius, temp, 15000.0);  // 40–50 mm/s, 50–60 °C, 15 kN: inside
  r.add(2.0, 0.1, radius, temp, 5000.0);   // 4 mm/s < 6 and 5 kN < 10 kN: one step, two ranges
  temp << 80.0, 95.0;
  r.add(3.0, 20.0, radius, temp, 30000.0);  // 1000 mm/s > 590, 95 °C > 90, 30 kN > 25
  r.add(4.0, 0.0, radius, temp, 15000.0);   // stuck: no speed count; 95 °C still above
  EXPECT_DOUBLE_EQ(r.total_s, 10.0);
  EXPECT_DOUBLE_EQ(r.outside_s, 9.0);
  EXPECT_DOUBLE_EQ(r.speed_below_s, 2.0);
  EXPECT_DOUBLE_EQ(r.speed_above_s, 3.0);
  EXPECT_DOUBLE_EQ(r.temp_above_s, 7.0);
  EXPECT_DOUBLE_EQ(r.load_below_s, 2.0);
  EXPECT_DOUBLE_EQ(r.load_above_s, 3.0);
  EXPECT_DOUBLE_EQ(r.min_speed_mm_s, 4.0);
  EXPECT_DOUBLE_EQ(r.max_speed_mm_s, 1000.0);
  const auto b = components::friction_range_block(r);
  EXPECT_DOUBLE_EQ(b.find_scalar("fraction_outside")->value, 0.9);
  EXPECT_THAT(b.find_text("summary")->value,
              ::testing::HasSubstr("clamp force up to 3e+04 N, above the data's 2.5e+04 N for 30 % of the run"));
}

TEST(FrictionDataRange, APrescribedSlipRunBelowTheMatrixLoadsSaysSoInItsBlock) {
  const clutch::Fluid fluid = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml");
  clutch::WetClutchParams p;
  p.start_temp_C = p.sump_start_temp_C = 60.0;
  rig_models::PrescribedSlipSettings s;
  s.duration_s = 2.0;
  const components::DriveCycle cycle{components::PiecewiseLinear({0.0}, {30.0}),
                                     components::PiecewiseLinear({0.0}, {5000.0})};
  const auto rec = rig_models::run_prescribed_slip(clutch::WetClutch(p, fluid), cycle, s);
  const auto* b = rec.find_block(components::kFrictionRangeBlock);
  ASSERT_NE(b, nullptr);
  EXPECT_DOUBLE_EQ(b->find_scalar("fraction_load_below")->value, 1.0);
  EXPECT_DOUBLE_EQ(b->find_scalar("fraction_speed_below")->value, 0.0);  // 30 rpm: 120–180 mm/s
  EXPECT_DOUBLE_EQ(b->find_scalar("law_min_load_N")->value, 10000.0);
  EXPECT_THAT(b->find_text("summary")->value,
              ::testing::HasSubstr("clamp force down to 5000 N, below the data's 1e+04 N for 100 % of the run"));
}

}  // namespace
