// The first-generation Haldex control unit (components/haldex_controller): the throttle valve's
// opening u = 1 − d from the demand d = max(s_x/s_lock, g·pedal), pedal ignored in a parking turn,
// limited at speed. Each expected opening is worked out by hand from the default thresholds
// (s_lock 20 rpm, g 0.5, parking below 15 km/h with the front axle > 2 % further, demand limited
// from 80 km/h to 0.3 at 160 km/h).
#include <gtest/gtest.h>

#include <stdexcept>

#include "components/haldex_controller.hpp"

namespace shudder::components {
namespace {

ControllerReading reading(double v_km_h, double front_rpm, double rear_rpm, double turn, double pedal) {
  return {v_km_h, front_rpm, rear_rpm, turn, pedal};
}

TEST(HaldexController, ShutsTheValveForSlipAndThePedalOpensItOtherwise) {
  const HaldexController c({});
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(30, 250, 250, 1.0, 0.0)), 1.0);  // cruising: open
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(30, 250, 250, 1.0, 1.0)), 0.5);  // full pedal: half
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(30, 260, 250, 1.0, 0.0)), 0.5);  // 10 rpm slip: half
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(30, 280, 250, 1.0, 0.0)), 0.0);  // 30 rpm: shut
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(30, 220, 250, 1.0, 0.0)), 0.0);  // either sign (overrun)
}

TEST(HaldexController, OpensInAParkingTurnUnlessAWheelSpins) {
  const HaldexController c({});
  // Full lock at 5 km/h: the front axle runs 10 % further than the rear, as the turn explains.
  const ControllerReading park = reading(5, 44, 40, 1.1, 1.0);
  EXPECT_TRUE(c.parking(park));
  EXPECT_DOUBLE_EQ(c.excess_slip_rpm(park), 0.0);
  EXPECT_DOUBLE_EQ(c.valve_opening(park), 1.0);                          // lets the coupling slip
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(5, 54, 40, 1.1, 1.0)), 0.5);  // 10 rpm more: traction
  // The same turn at 30 km/h is no parking manoeuvre: the pedal counts.
  EXPECT_FALSE(c.parking(reading(30, 264, 240, 1.1, 1.0)));
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(30, 264, 240, 1.1, 1.0)), 0.5);
  // A gentle curve at parking speed is not a parking turn either.
  EXPECT_FALSE(c.parking(reading(5, 40.4, 40, 1.01, 1.0)));
}

TEST(HaldexController, LimitsTheDemandAtSpeed) {
  const HaldexController c({});
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(160, 1500, 1400, 1.0, 1.0)), 0.7);     // capped at 0.3
  EXPECT_NEAR(c.valve_opening(reading(120, 1100, 1000, 1.0, 1.0)), 0.35, 1e-12);  // halfway: 1 − 0.65
  EXPECT_DOUBLE_EQ(c.valve_opening(reading(80, 800, 700, 1.0, 1.0)), 0.0);
}

TEST(HaldexController, RejectsInconsistentThresholds) {
  HaldexControllerParams p;
  p.lock_slip_rpm = 0;
  EXPECT_THROW(HaldexController{p}, std::invalid_argument);
  p = {};
  p.top_speed_km_h = p.fast_speed_km_h;
  EXPECT_THROW(HaldexController{p}, std::invalid_argument);
  p = {};
  p.pedal_gain = 1.5;
  EXPECT_THROW(HaldexController{p}, std::invalid_argument);
}

}  // namespace
}  // namespace shudder::components
