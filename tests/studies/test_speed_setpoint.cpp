// The speed set point recovered by inverting the rig's speed loop (studies/speed_setpoint).
//
//   * steady sliding: the drive runs at its set point, so the estimate is the drive speed;
//   * a load ramp T = T0 + r t: a PI loop (kp, ki) settles with the drive lagging by r / ki
//     (the integrator must grow at r, ki E' = ki e = r), so the estimate is ω + r / ki;
//   * a simulated stick-slip run on the 100 Hz bar at 0.5 rpm, from 1 kHz recordings averaged
//     over 0.05 s windows as the replay does: the drive crawls at ~0.12 rpm while stuck and
//     races to ~1.6 rpm after breakaway, yet the estimate stays within 0.1 rpm of the true
//     0.5 rpm and averages to it within 0.01 rpm — with the motor's torque ripple on, which the
//     estimate subtracts (blind to it, the windows are off by more than 0.1 rpm).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/units.hpp"
#include "io/scenario.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "studies/speed_setpoint.hpp"
#include "tests/support/models.hpp"
#include "tests/support/recording.hpp"

namespace shudder::studies {

// The machines these studies are made of.
using namespace rig_models;

namespace {

// The closed forms below are for a loop without the motor's torque ripple (their inputs carry
// none), so the estimator is told there is none.
RigParams without_ripple() {
  RigParams rig;
  rig.motor_ripple.amplitude_Nm = 0.0;
  return rig;
}

TEST(SpeedSetpoint, SteadySlidingGivesTheDriveSpeed) {
  const RigParams rig = without_ripple();  // steady start
  const std::vector<double> t{0.0, 0.001, 0.002, 0.004}, speed(4, 10.0), torque(4, 80.0);
  for (double v : studies::estimate_speed_setpoint(t, speed, torque, rig)) EXPECT_NEAR(v, 10.0, 1e-12);
}

TEST(SpeedSetpoint, LoadRampAddsTheLoopsLag) {
  const RigParams rig = without_ripple();
  const SpeedLoopGains g = speed_loop_gains(rig);
  const double rate_Nm_s = 95.0, set_rpm = 0.5;  // the stuck phase of the 0.5 rpm probe
  const double lag_rpm = units::rad_s_to_rpm(rate_Nm_s / g.ki_Nm_per_rad);
  std::vector<double> t, w, torque;
  for (int k = 0; k < 2000; ++k) {
    t.push_back(0.001 * k);
    w.push_back(set_rpm - lag_rpm);
    torque.push_back(20.0 + rate_Nm_s * t.back());
  }
  const auto sp = studies::estimate_speed_setpoint(t, w, torque, rig);
  // The estimator starts as if sliding steadily (no lag), so it needs a few τ = kp/ki = 32 ms;
  // after 10 τ that start is e^-10 ≈ 5e-5 of the lag, and the filter is exact for a torque
  // linear between samples: 1e-3 of the set point is a margin of 20 over what is left.
  const double tau_s = g.kp_Nms_per_rad / g.ki_Nm_per_rad;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] > 10 * tau_s) {
      EXPECT_NEAR(sp[k], set_rpm, 1e-3 * set_rpm) << "t = " << t[k];
    }
  EXPECT_GT(lag_rpm, 0.3);  // the case matters: the drive runs at a quarter of its set point
}

TEST(SpeedSetpoint, RejectsMismatchedInputs) {
  EXPECT_THROW(studies::estimate_speed_setpoint({0.0, 1.0}, {1.0, 1.0}, {5.0}, RigParams{}), std::invalid_argument);
  EXPECT_THROW(studies::estimate_speed_setpoint({0.0, 0.0}, {1.0, 1.0}, {5.0, 5.0}, RigParams{}),
               std::invalid_argument);
}

// Window means as the replay takes them (consecutive 0.05 s windows at their mean times).
components::PiecewiseLinear window_means(const std::vector<double>& t, const std::vector<double>& x) {
  std::vector<double> tm, xm;
  for (std::size_t b = 0; b < t.size();) {
    std::size_t e = b;
    double st = 0, sx = 0;
    for (; e < t.size() && t[e] < t[b] + 0.05; ++e) {
      st += t[e];
      sx += x[e];
    }
    tm.push_back(st / static_cast<double>(e - b));
    xm.push_back(sx / static_cast<double>(e - b));
    b = e;
  }
  return {tm, xm};
}

TEST(SpeedSetpoint, RecoversTheSetPointOfAStickSlipRun) {
  io::Scenario sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/rig_stick_time_probe.toml");
  // The motor's torque ripple is on (default 1 N m, 576/rev: 4.8 Hz at 0.5 rpm); the estimate
  // subtracts it before inverting the loop.
  ASSERT_EQ(shudder::test::rig_model(sc).params.motor_ripple.amplitude_Nm, 1.0);
  shudder::test::rig_model(sc).params.stick_time.enabled = true;
  shudder::test::rig_model(sc).params.stick_time.max_increase = 0.15;
  shudder::test::rig_model(sc).params.stick_time.time_constant_s = 0.05;
  const auto rec = run_rig(shudder::test::rig_model(sc).params, sc.make_clutch(), shudder::test::rig_model(sc).cycle,
                           shudder::test::rig_model(sc).settings);
  const auto& t = test::signal(rec, "time_s");
  const auto& drive = test::signal(rec, "speed_rpm");
  const auto speed = window_means(t, drive);
  const auto sp = window_means(t, studies::estimate_speed_setpoint(t, drive, test::signal(rec, "torque_Nm"),
                                                                   shudder::test::rig_model(sc).params));
  double worst_drive = 0, worst_estimate = 0, mean = 0;
  int n = 0;
  for (std::size_t k = 0; k < sp.values().size(); ++k) {
    if (sp.times_s()[k] < 0.1) continue;  // the start from rest
    worst_drive = std::max(worst_drive, std::abs(speed.values()[k] - 0.5));
    worst_estimate = std::max(worst_estimate, std::abs(sp.values()[k] - 0.5));
    mean += sp.values()[k];
    ++n;
  }
  mean /= n;
  ::testing::Test::RecordProperty("worst_window_error_rpm", std::to_string(worst_estimate));
  ::testing::Test::RecordProperty("mean_rpm", std::to_string(mean));
  std::printf("drive speed off its set point by up to %.3f rpm; estimate by up to %.3f rpm, mean %.4f rpm\n",
              worst_drive, worst_estimate, mean);
  EXPECT_GT(worst_drive, 0.3);
  // Left in the estimate: the housing's inertia (J_h ω_h', 0.02 kg m² ringing at 100 Hz after
  // breakaway), which shifts the window holding a slip by ~J_h Δω_h / (kp L) ≈ 0.08 rpm; the
  // stuck windows are exact to 1e-3 rpm.
  EXPECT_LT(worst_estimate, 0.1);
  EXPECT_NEAR(mean, 0.5, 0.01);

  // The same inversion blind to the ripple (the replay before it accounted for the ripple) reads the
  // ripple as a speed error of T_r / kp = 0.13 rpm, which the 0.05 s windows (a quarter of the
  // ripple's period) do not average away: the windows wobble by about that much.
  RigParams blind = shudder::test::rig_model(sc).params;
  blind.motor_ripple.amplitude_Nm = 0.0;
  const auto sp_blind =
      window_means(t, studies::estimate_speed_setpoint(t, drive, test::signal(rec, "torque_Nm"), blind));
  double worst_blind = 0;
  for (std::size_t k = 0; k < sp_blind.values().size(); ++k)
    if (sp_blind.times_s()[k] >= 0.1) worst_blind = std::max(worst_blind, std::abs(sp_blind.values()[k] - 0.5));
  std::printf("blind to the ripple: estimate off by up to %.3f rpm\n", worst_blind);
  EXPECT_GT(worst_blind, 0.1);
}

}  // namespace
}  // namespace shudder::studies
