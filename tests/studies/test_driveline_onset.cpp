// For the driveline: a judder onset set by physics, not by the slow step.
//
// scenarios/driveline_coastdown_judder.toml: over the first 2 s the coupling is taken up (valve
// setting 0.1 → 1.8 bar, engine braking 0 → −10 N m), then it slides steadily on the curve's
// kinematic slip while the car slows. The slip falls with the speed, the falling μ–v branch's
// negative damping (n r F dμ/dv, dμ/dv ∝ 1/v) grows, and the linear stability analysis of the
// slipping coupling (studies/driveline_stability.hpp) turns unstable at ~20 rpm (8.37 s).
// The seed is the engine's firing pulsation: its 2nd order falls with the engine's speed and
// passes the 45 Hz coupling mode (the coupling's output side with the rear differential) at
// ~8.5 s, where the judder starts and then holds itself at the mode (checked below).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/shudder_detection.hpp"
#include "core/units.hpp"
#include "io/scenario.hpp"
#include "studies/driveline_stability.hpp"
#include "components/energy_guard.hpp"
#include "rig_models/model.hpp"
#include "studies/recording_detection.hpp"

namespace shudder::studies {

// The machines these studies are made of.
using namespace rig_models;

namespace {

struct CoastDown {
  io::Scenario sc;
  dynamics::Recording rec;
  analysis::ShudderResult verdict;  // the run's judgement (`shudder run`): the threshold-crossing onset
};

// The shipped scenario with its slow (thermal and hydraulic) step scaled, optionally without the
// engine's firing pulsation.
CoastDown coast_down(double step_factor, bool pulsation = true) {
  CoastDown r{
      io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_coastdown_judder.toml"), {}, {}};
  auto& m = std::get<DrivelineModel>(r.sc.model);
  m.settings.slow_step_s *= step_factor;
  if (!pulsation) m.params.engine_pulsation.amplitude_Nm = 0.0;
  r.rec = simulate(m, r.sc.make_clutch());
  r.verdict = studies::judge_recording(*studies::recording_detection(r.rec));
  return r;
}

// The criterion: halving the thermal step (10 → 5 → 2.5 ms; in the driveline it is also
// the hydraulics' and the controller's step) moves the run's onset by < 5 %, with the verdict
// unchanged. Measured (shared machine): 8.4684 / 8.4692 / 8.4689 s (+0.01 %, −0.004 %).
// What would fail: a start transient above the threshold (the clamp applied as a step, as in
// driveline_takeup_judder) puts the onset at 0 whatever the step — hence the onset must come
// after the take-up.
TEST(DrivelineOnset, CoastDownOnsetChangesLessThanFivePercentWhenTheThermalStepIsHalved) {
  const CoastDown a = coast_down(1.0), b = coast_down(0.5), c = coast_down(0.25);
  std::printf(
      "coast-down judder, thermal step 10 / 5 / 2.5 ms: onset %.4f / %.4f / %.4f s, %.2f / %.2f / %.2f Hz, "
      "%.2f / %.2f / %.2f N m\n",
      a.verdict.onset_time_s, b.verdict.onset_time_s, c.verdict.onset_time_s, a.verdict.frequency_Hz,
      b.verdict.frequency_Hz, c.verdict.frequency_Hz, a.verdict.amplitude_Nm, b.verdict.amplitude_Nm,
      c.verdict.amplitude_Nm);
  for (const CoastDown* r : {&a, &b, &c}) {
    auto old_onset = *studies::recording_detection(r->rec);  // the figure quoted above, printed only
    old_onset.settings.onset_definition = analysis::OnsetDefinition::kGrowthLine;
    std::printf("  onset by the growth line: %.4f s\n",
                analysis::detect_shudder(old_onset.input, old_onset.settings).onset_time_s);
    EXPECT_EQ(r->verdict.verdict, analysis::Verdict::kVibration);
    // The coupling mode the linear analysis finds at the judged window's mean point (45.19 Hz);
    // the limit cycle runs 0.6 % above it (its slip swings off the point): 5 %.
    const auto& model = std::get<DrivelineModel>(r->sc.model);
    const auto clutch = r->sc.make_clutch();
    const double mode_Hz =
        studies::least_damped_slipping_mode(
            HaldexDriveline(model.params, clutch, model.manoeuvre), clutch,
            studies::recorded_operating_point(r->rec, r->verdict.oscillating_from_s, r->verdict.oscillating_to_s))
            .frequency_Hz;
    EXPECT_NEAR(r->verdict.frequency_Hz, mode_Hz, 0.05 * mode_Hz);
    // Grown out of steady sliding, not left over from the start: after the 2 s take-up.
    EXPECT_GT(r->verdict.onset_time_s, 3.0);
    // The energy accounts close at every step (components/energy_guard.hpp: 1e-6 / 1e-3).
    EXPECT_EQ(components::energy_balance_violation(r->rec), "");
  }
  EXPECT_LT(std::abs(b.verdict.onset_time_s / a.verdict.onset_time_s - 1.0), 0.05);
  EXPECT_LT(std::abs(c.verdict.onset_time_s / b.verdict.onset_time_s - 1.0), 0.05);
}

// The physical meaning of the onset. Along the run, the linear analysis at the recorded mean
// operating point (car speed, slip, clamp force, interface temperature, tyre forces over 50 ms)
// gives the slipping coupling's growth rate σ(t); it crosses zero at t_c, as the slip falls with
// the car's speed and the falling branch's negative damping grows. The judder is the mode that
// turns unstable: its onset follows t_c, and its frequency is that mode's.
TEST(DrivelineOnset, LinearAnalysisTurnsUnstableJustBeforeTheOnset) {
  const CoastDown r = coast_down(1.0);
  ASSERT_EQ(r.verdict.verdict, analysis::Verdict::kVibration);
  const auto& model = std::get<DrivelineModel>(r.sc.model);
  const auto clutch = r.sc.make_clutch();
  const HaldexDriveline dl(model.params, clutch, model.manoeuvre);
  constexpr double kTakeUp_s = 2.0, kWindow_s = 0.05;
  double t_c = std::nan(""), previous = std::nan(""), mode_Hz = std::nan("");
  for (double t = kTakeUp_s; t + kWindow_s <= r.verdict.onset_time_s; t += kWindow_s) {
    const studies::CouplingMode m =
        studies::least_damped_slipping_mode(dl, clutch, studies::recorded_operating_point(r.rec, t, t + kWindow_s));
    const double mid = t + 0.5 * kWindow_s;
    if (std::isnan(t_c) && previous < 0 && m.growth_per_s >= 0) {
      t_c = mid - kWindow_s * m.growth_per_s / (m.growth_per_s - previous);
      mode_Hz = m.frequency_Hz;
    }
    previous = m.growth_per_s;
  }
  ASSERT_TRUE(std::isfinite(t_c)) << "the linear analysis never turned unstable";
  std::printf("linear analysis: unstable from %.3f s at %.2f Hz; onset %.4f s at %.2f Hz\n", t_c, mode_Hz,
              r.verdict.onset_time_s, r.verdict.frequency_Hz);
  // Measured: unstable from 8.371 s (the 31.5 Hz mode first), onset 8.468 s at 45.5 Hz. The onset
  // follows the crossing within a second: the seed, the firing pulsation's forced response at the
  // 45 Hz mode (below), is already well above the take-up's ringing. Which mode judders is the
  // one the seed feeds: at the judged window's mean point the least-damped mode is the 45 Hz one
  // (the first test: within 5 %).
  EXPECT_LT(t_c, r.verdict.onset_time_s);
  EXPECT_GT(t_c, r.verdict.onset_time_s - 1.0);
}

// The seed is the engine's firing pulsation: its 2nd order (2 n/60 for four cylinders) falls with
// the car's speed and passes the 45 Hz coupling mode just as that mode turns unstable, so the
// onset comes at that crossing. Without the pulsation only the take-up's ringing seeds the mode,
// and by the run's end it has not grown into a 45 Hz verdict.
TEST(DrivelineOnset, CoastDownSeedIsTheFiringPulsationsSecondOrder) {
  const CoastDown with = coast_down(1.0), without = coast_down(1.0, false);
  ASSERT_EQ(with.verdict.verdict, analysis::Verdict::kVibration);
  const auto& t = with.rec.find("time_s")->values;
  const auto& n = with.rec.find("engine_speed_rpm")->values;
  const auto at = std::lower_bound(t.begin(), t.end(), with.verdict.onset_time_s) - t.begin();
  const auto& model = std::get<DrivelineModel>(with.sc.model);
  const double order_Hz = 0.5 * model.params.engine_pulsation.cylinders * n[static_cast<std::size_t>(at)] / 60.0;
  std::printf("onset %.4f s: judder %.2f Hz, firing order %.2f Hz; without the pulsation: verdict %d at %.2f Hz\n",
              with.verdict.onset_time_s, with.verdict.frequency_Hz, order_Hz, static_cast<int>(without.verdict.verdict),
              without.verdict.frequency_Hz);
  EXPECT_NEAR(order_Hz, with.verdict.frequency_Hz, 0.05 * with.verdict.frequency_Hz);
  const bool judders_at_45 = without.verdict.verdict == analysis::Verdict::kVibration &&
                             std::abs(without.verdict.frequency_Hz / with.verdict.frequency_Hz - 1.0) < 0.1;
  EXPECT_FALSE(judders_at_45);
}

}  // namespace
}  // namespace shudder::studies
