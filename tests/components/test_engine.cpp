// The engine map with its idle governor (components/engine.hpp) against closed forms, alone and in
// the driveline:
//   * the governor's balance: with the throttle shut the speed settles where K_gov (ω_idle − ω)
//     equals the losses (and, in the car, the road load reflected to the crankshaft);
//   * the torque–speed slope is the map's: on a straight stretch of the full-load curve,
//     dT/dω = ΔT_full/Δω − dT_loss/dω;
//   * stall: a load the governor cannot carry pulls the engine below its stall speed, and the
//     run says when; an engine that can carry it never stalls.
#include <gtest/gtest.h>

#include <cmath>

#include "core/units.hpp"
#include "io/scenario.hpp"
#include "components/engine.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "tests/support/recording.hpp"

namespace shudder::components {
namespace {

double loss_Nm(const EngineParams& p, double w) {
  return (p.loss_torque_idle_Nm +
          (p.loss_torque_max_Nm - p.loss_torque_idle_Nm) * units::rad_s_to_rpm(w) / p.max_speed_rpm) *
         std::tanh(w / 10.0);
}

TEST(Engine, ShutThrottleSettlesWhereTheGovernorCarriesTheLosses) {
  const EngineParams p;
  const Engine e(p);
  // Fixed point of ω = ω_idle − T_loss(ω)/K.
  double w = units::rpm_to_rad_s(p.idle_speed_rpm);
  for (int i = 0; i < 50; ++i)
    w = units::rpm_to_rad_s(p.idle_speed_rpm) - loss_Nm(p, w) / p.idle_governor_gain_Nms_per_rad;
  EXPECT_NEAR(e.torque_Nm(w, 0.0), 0.0, 1e-9);
  EXPECT_GT(e.torque_Nm(w - 1.0, 0.0), 0.0);  // below: the governor pushes up
  EXPECT_LT(e.torque_Nm(w + 1.0, 0.0), 0.0);  // above: the losses pull down
}

TEST(Engine, SlopeIsTheMapsOnAStraightStretch) {
  const EngineParams p;
  const Engine e(p);
  const double w = units::rpm_to_rad_s(3000.0);  // on 2400–4000 rpm: 170 → 160 N m
  const double per_rpm_to_per_rad_s = units::rad_s_to_rpm(1.0);
  const double expected = (160.0 - 170.0) / (4000.0 - 2400.0) * per_rpm_to_per_rad_s -
                          (p.loss_torque_max_Nm - p.loss_torque_idle_Nm) / p.max_speed_rpm * per_rpm_to_per_rad_s;
  // Central difference of a linear stretch (tanh(ω/10) = 1 to 1e-130 there): rounding only.
  EXPECT_NEAR(e.torque_speed_slope_Nms_per_rad(w, 1.0), expected, 1e-6);
  EXPECT_NEAR(e.torque_Nm(w, 1.0), 170.0 - 10.0 * 600.0 / 1600.0 - loss_Nm(p, w), 1e-9);
}

TEST(Engine, RejectsIdleBelowStall) {
  EngineParams p;
  p.idle_speed_rpm = 300.0;
  EXPECT_THROW(Engine{p}, std::invalid_argument);
}

io::Scenario pack() {
  io::Scenario sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_tight_turn.toml");
  return sc;
}

TEST(Engine, IdlesTheCarAtTheGovernorsBalance) {
  const auto sc = pack();
  const auto clutch = sc.make_clutch();
  rig_models::DrivelineParams p;
  rig_models::DrivelineInputs in;
  in.throttle = PiecewiseLinear({0.0}, {0.0});
  in.start_speed_km_h = 10.0;  // 1160 rpm in 1st: the engine brakes the car down to idle
  rig_models::DrivelineSettings s;
  s.duration_s = 8.0;
  const auto rec = rig_models::run_driveline(p, clutch, in, s);
  // Balance at the crankshaft: K (ω_idle − ω) = T_loss(ω) + F_road(v) r / i, v = ω r / i.
  const rig_models::HaldexDriveline dl(p, clutch, in);
  const double i = p.gear_ratio * p.final_drive_ratio, r = p.wheel_radius_m;
  double w = units::rpm_to_rad_s(p.engine.idle_speed_rpm);
  for (int k = 0; k < 100; ++k)
    w = units::rpm_to_rad_s(p.engine.idle_speed_rpm) -
        (loss_Nm(p.engine, w) + dl.road_load().force_N(w * r / i) * r / i) / p.engine.idle_governor_gain_Nms_per_rad;
  // 0.5 %: the tyres' slip under the road load (~1e-3) and what is left of the settling.
  EXPECT_NEAR(test::signal(rec, "engine_speed_rpm").back(), units::rad_s_to_rpm(w), 0.005 * units::rad_s_to_rpm(w));
  EXPECT_TRUE(std::isnan(test::scalar(rec, "engine_stall_time_s")));
  // At idle the governor's slope −K dominates: the engine damps the driveline.
  EXPECT_LT(test::scalar(rec, "engine_torque_speed_slope_Nms_per_rad"), -0.5 * p.engine.idle_governor_gain_Nms_per_rad);
  EXPECT_LT(test::scalar(rec, "mechanical_energy_relative_error"), 1e-6);
}

TEST(Engine, StallsOnAGradeTheGovernorCannotHold) {
  const auto sc = pack();
  const auto clutch = sc.make_clutch();
  rig_models::DrivelineParams p;
  rig_models::DrivelineInputs in;
  in.throttle = PiecewiseLinear({0.0}, {0.0});
  in.start_speed_km_h = 7.0;
  rig_models::DrivelineSettings s;
  s.duration_s = 3.0;
  // 30 %: m g sin θ r / i = 109 N m at the crankshaft, more than full load at idle (87 N m).
  in.grade_percent = 30.0;
  const auto stalled = rig_models::run_driveline(p, clutch, in, s);
  EXPECT_GT(test::scalar(stalled, "engine_stall_time_s"), 0.0);
  EXPECT_LT(test::signal(stalled, "engine_speed_rpm").back(), p.engine.stall_speed_rpm);
  // 5 %: 18 N m, which the governor carries.
  in.grade_percent = 5.0;
  const auto held = rig_models::run_driveline(p, clutch, in, s);
  EXPECT_TRUE(std::isnan(test::scalar(held, "engine_stall_time_s")));
}

}  // namespace
}  // namespace shudder::components
