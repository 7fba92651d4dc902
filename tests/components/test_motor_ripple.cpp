// The drive's torque ripple (components/motor_ripple.hpp), the physical seed of the rig's
// friction-induced vibration.
//
// Old behaviour (before the ripple): the only disturbance of a steady sliding start was the
// torque step the contact law takes at each thermal step (the held ring temperatures change
// stepwise), so the onset time of rig_shudder_negative_slope followed the thermal step. The
// tests below show that an isothermal unstable run oscillates only with the ripple, and that with
// the defaults (ripple on, 1 N m) halving the thermal step moves the onset of every shipped rig
// scenario that shudders by less than 5 % (the criterion).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <numbers>
#include <string>

#include "analysis/shudder_detection.hpp"
#include "io/input_error.hpp"
#include "io/scenario.hpp"
#include "components/energy_guard.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "components/motor_ripple.hpp"
#include "studies/recording_detection.hpp"
#include "tests/support/models.hpp"

namespace {

using shudder::components::MotorRipple;
using shudder::components::MotorRippleTorque;
using shudder::components::PiecewiseLinear;
constexpr double kPi = std::numbers::pi;

// Closed form at constant speed: T = A sin(2π N n t / 60). On a ramp n = a t (rpm, a in rpm/s)
// the angle is a t²/120 revolutions. Tolerance: the phase is ~1e3 rad, so 1e-12 relative.
TEST(MotorRipple, TorqueIsTheSineOfTheReferenceAngle) {
  const MotorRipple r{2.0, 576.0};
  const MotorRippleTorque steady(r, PiecewiseLinear({0.0}, {30.0}));
  for (double t : {0.0, 1e-4, 0.0123, 1.7})
    EXPECT_NEAR(steady(t), 2.0 * std::sin(2.0 * kPi * 576.0 * 30.0 * t / 60.0), 1e-9) << t;
  // Ramp 0 -> 100 rpm over 1 s, then held: after the ramp the angle is 100/120 rev + 100/60 (t-1).
  const MotorRippleTorque ramp(r, PiecewiseLinear({0.0, 1.0}, {0.0, 100.0}));
  for (double t : {0.3, 0.77}) EXPECT_NEAR(ramp(t), 2.0 * std::sin(2.0 * kPi * 576.0 * 100.0 * t * t / 120.0), 1e-9);
  const double t = 1.25;
  EXPECT_NEAR(ramp(t), 2.0 * std::sin(2.0 * kPi * 576.0 * (100.0 / 120.0 + 100.0 / 60.0 * (t - 1.0))), 1e-9);
  EXPECT_EQ(MotorRippleTorque({0.0, 576.0}, PiecewiseLinear({0.0}, {30.0}))(0.01), 0.0);
}

TEST(MotorRipple, RejectsNegativeAmplitudeAndNonPositivePeriods) {
  const PiecewiseLinear n({0.0}, {30.0});
  EXPECT_THROW(MotorRippleTorque({-1.0, 576.0}, n), std::invalid_argument);
  EXPECT_THROW(MotorRippleTorque({1.0, 0.0}, n), std::invalid_argument);
  EXPECT_THROW(MotorRippleTorque({1.0, std::nan("")}, n), std::invalid_argument);
}

// The run's verdict, its onset (definition 8 of analysis/shudder_detection.hpp) and the time
// the torque-cell signal first leaves its start value by 10 N m (about a tenth of the limit
// cycle's swing: where the growing oscillation becomes visible on the rig's torque trace).
struct Onset {
  shudder::analysis::Verdict verdict;
  double detector_s, visible_s;
};

// The shipped negative-slope scenario with the given ripple amplitude and thermal step, run for
// 1 s (the oscillation is established by ~0.45 s, measured).
Onset onset(double ripple_Nm, double thermal_step_s) {
  auto sc = shudder::io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/rig_shudder_negative_slope.toml");
  auto& m = shudder::test::rig_model(sc);
  m.params.motor_ripple.amplitude_Nm = ripple_Nm;
  m.settings.thermal_step_s = thermal_step_s;
  m.settings.duration_s = 1.0;
  const auto rec = shudder::rig_models::run_rig(m.params, sc.make_clutch(), m.cycle, m.settings);
  const auto det = shudder::studies::recording_detection(rec);
  EXPECT_TRUE(det.has_value());
  const auto r = shudder::studies::judge_recording(*det);
  const auto& t = rec.find("time_s")->values;
  const auto& q = rec.find("torque_Nm")->values;
  double visible = std::nan("");
  for (std::size_t k = 0; k < t.size() && std::isnan(visible); ++k)
    if (std::abs(q[k] - q[0]) > 10.0) visible = t[k];
  std::printf("ripple %.3g N m, thermal step %.3g ms: verdict %s, onset %.4f s, 10 N m swing at %.4f s\n", ripple_Nm,
              thermal_step_s * 1e3, std::string(to_string(r.verdict)).c_str(), r.onset_time_s, visible);
  return {r.verdict, r.onset_time_s, visible};
}

// The criterion: halving the thermal step (10 -> 5 ms) moves the onset by < 5 %, on
// the detector's onset and on the visible one (measured: 1.8 % and 0.7 %).
TEST(MotorRipple, NegativeSlopeOnsetChangesLessThanFivePercentWhenTheThermalStepIsHalved) {
  const Onset a = onset(1.0, 0.010), b = onset(1.0, 0.005);
  ASSERT_EQ(a.verdict, shudder::analysis::Verdict::kVibration);
  ASSERT_EQ(b.verdict, shudder::analysis::Verdict::kVibration);
  EXPECT_LT(std::abs(b.detector_s / a.detector_s - 1.0), 0.05);
  EXPECT_LT(std::abs(b.visible_s / a.visible_s - 1.0), 0.05);
}

// Without thermal steps during the run (one thermal step longer than the run: the clutch is
// isothermal, the network autonomous), the unstable steady sliding state must still start to
// oscillate: physics, not the thermal step, seeds it. Old behaviour (no ripple; reproduced here
// with torque_ripple_Nm = 0): the run stays flat, verdict none, no onset at all.
TEST(MotorRipple, UnstableSlidingOscillatesWithoutThermalSteps) {
  const Onset without = onset(0.0, 10.0);
  EXPECT_EQ(without.verdict, shudder::analysis::Verdict::kNone);
  EXPECT_TRUE(std::isnan(without.visible_s));
  const Onset with = onset(1.0, 10.0);
  EXPECT_EQ(with.verdict, shudder::analysis::Verdict::kVibration);
  // The seed grows at σ ≈ 13.4 1/s: from the ripple's ~3e-3 N m forced floor at the bar mode to
  // 10 N m takes ln(10/3e-3)/13.4 ≈ 0.6 s (measured 0.59 s). Bounds: within the 1 s run, and
  // not at the start (the ripple's own forced response is far below 10 N m).
  EXPECT_GT(with.visible_s, 0.3);
  EXPECT_LT(with.visible_s, 1.0);
}

}  // namespace

namespace {

// The ripple must not make a stable case shudder: Paper G Case 2 on the 378 Hz bar (thesis: no
// shudder) keeps verdict none with the estimated 1 N m ripple. Its forced response is the ripple over
// the drive's inertia, far below the detector's amplitude threshold.
TEST(MotorRipple, StableRigCaseStaysWithoutShudder) {
  auto sc = shudder::io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/rig_case2_15kN_378Hz.toml");
  auto& m = shudder::test::rig_model(sc);
  ASSERT_EQ(m.params.motor_ripple.amplitude_Nm, 1.0);  // the default: the estimate (motor_ripple.hpp)
  const auto rec = shudder::rig_models::run_rig(m.params, sc.make_clutch(), m.cycle, m.settings);
  const auto det = shudder::studies::recording_detection(rec);
  ASSERT_TRUE(det.has_value());
  EXPECT_EQ(shudder::studies::judge_recording(*det).verdict, shudder::analysis::Verdict::kNone);
}

}  // namespace

namespace {

std::string negative_slope_with(const std::string& motor_keys) {
  const std::string text =
      "[scenario]\nname = \"x\"\ntype = \"rig\"\nduration_s = 1.0\n"
      "[clutch]\nfluid = \"fluids/schematic_negative_slope.toml\"\nstart_temp_C = 60.0\n"
      "[drive]\ntime_s = [0.0, 1.0]\nspeed_rpm = [30.0, 30.0]\nnormal_force_N = 15000.0\n"
      "[rig.motor]\n" +
      motor_keys + "\n";
  return text;
}
const std::string kPath = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/ripple.toml";

TEST(MotorRipple, ScenarioKeysSetTheRippleWithinTheirBounds) {
  auto sc = shudder::io::load_scenario_text(
      negative_slope_with("torque_ripple_Nm = 0.0\ntorque_ripple_periods_per_rev = 96"), kPath);
  EXPECT_EQ(shudder::test::rig_model(sc).params.motor_ripple.amplitude_Nm, 0.0);
  EXPECT_EQ(shudder::test::rig_model(sc).params.motor_ripple.periods_per_rev, 96.0);
  try {
    shudder::io::load_scenario_text(negative_slope_with("torque_ripple_Nm = 60.0"), kPath);
    ADD_FAILURE() << "60 N m accepted";
  } catch (const shudder::io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.motor.torque_ripple_Nm"), std::string::npos) << e.what();
  }
  EXPECT_THROW(shudder::io::load_scenario_text(negative_slope_with("torque_ripple_periods_per_rev = 0.5"), kPath),
               shudder::io::InputError);
}

}  // namespace

namespace {

// The criterion on every shipped rig scenario, as shipped (the defaults: ripple on):
// halving the thermal step (10 -> 5 ms) moves the reported onset (the run's judgement:
// the detector's threshold-crossing onset, the oscillation reaching the verdict's threshold) by < 5 %, and a
// further halving (2.5 ms) agrees with 5 ms to < 5 % as well (convergence). Scenarios judged
// "none" have no onset; the others must agree in verdict and onset.
// Fails on the code before the first-order hold and that onset (docs/rig_model.md, "Onset and the thermal step"):
// with the ring temperatures held over the thermal step, the 10 ms staircase's 3rd harmonic
// sits on the 300 Hz bars (rig_ramp_peak10 2.739 / 2.992 s, +9.2 %; rig_ramp_thermal +8.0 %;
// sweep_torsion_bar 0.582 / 1.072 s, +84 %); with the first-order hold but the old onset (the growth line,
// from the start level) the two growths from the start scatter (rig_shudder_negative_slope
// 0.028 / 0.035 s, +25 %; sweep_torsion_bar 0.151 / 0.120 s, −20 %).
class ShippedRigOnset : public ::testing::TestWithParam<const char*> {};

TEST_P(ShippedRigOnset, ChangesLessThanFivePercentWhenTheThermalStepIsHalved) {
  const auto judge = [&](double step_factor) {
    auto sc = shudder::io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/" + GetParam() + ".toml");
    auto& m = shudder::test::rig_model(sc);
    m.settings.thermal_step_s *= step_factor;
    const auto rec = shudder::rig_models::run_rig(m.params, sc.make_clutch(), m.cycle, m.settings);
    // The hold changes what the friction reads, not the energy accounts: the run's guard
    // (thermal 1e-6, mechanical 1e-3, components/energy_guard.hpp) passes at every step size.
    EXPECT_EQ(shudder::components::energy_balance_violation(rec), "") << step_factor;
    const auto det = shudder::studies::recording_detection(rec);
    EXPECT_TRUE(det.has_value());
    return shudder::studies::judge_recording(*det);
  };
  const auto a = judge(1.0), b = judge(0.5), c = judge(0.25);
  std::printf("%s: verdict %s / %s / %s, onset %.4f / %.4f / %.4f s\n", GetParam(),
              std::string(to_string(a.verdict)).c_str(), std::string(to_string(b.verdict)).c_str(),
              std::string(to_string(c.verdict)).c_str(), a.onset_time_s, b.onset_time_s, c.onset_time_s);
  ASSERT_EQ(a.verdict, b.verdict);
  ASSERT_EQ(b.verdict, c.verdict);
  if (a.verdict == shudder::analysis::Verdict::kNone) return;
  EXPECT_LT(std::abs(b.onset_time_s / a.onset_time_s - 1.0), 0.05);
  EXPECT_LT(std::abs(c.onset_time_s / b.onset_time_s - 1.0), 0.05);
}

INSTANTIATE_TEST_SUITE_P(MotorRipple, ShippedRigOnset,
                         ::testing::Values("rig_shudder_negative_slope", "rig_ramp_peak10", "rig_ramp_peak20",
                                           "rig_ramp_thermal", "sweep_torsion_bar", "rig_stick_slip",
                                           "rig_stick_time_probe", "rig_case2_15kN_175Hz", "rig_case2_15kN_378Hz",
                                           "rig_case1_25kN_378Hz"));

}  // namespace

namespace {

// A thermal state that diverges is a numerical failure, not a run that creeps on: a rig part of
// 1 J/K behind 1000 W/K (values a diagnosis fit may try) makes the thermal update blow up
// within half a second (1e94 °C on the stick-time probe). Held temperatures gave a non-finite
// state and an exception there; the first-order hold fed the integrator friction at such
// temperatures and it crept on for minutes. Now run_multirate throws once a temperature leaves
// ±1e4 °C.
TEST(MultirateHold, ADivergingThermalStateIsANumericalFailure) {
  const std::string path = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/rig_stick_time_probe.toml";
  std::ifstream in(path);
  std::stringstream buf;
  buf << in.rdbuf();
  std::string text = buf.str();
  text += "\n[effects.rig_heat_capacity]\nenabled = true\nheat_capacity_J_per_K = 1.0\nconductance_W_per_K = 1000.0\n";
  auto sc = shudder::io::load_scenario_text(text, path);
  auto& m = shudder::test::rig_model(sc);
  try {
    shudder::rig_models::run_rig(m.params, sc.make_clutch(), m.cycle, m.settings);
    ADD_FAILURE() << "the diverging run finished";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("thermal step diverged at t = "), std::string::npos) << e.what();
  }
}

}  // namespace
