// For the driveline: a judder onset set by physics, not by the slow step.
//
// scenarios/driveline_coastdown_judder.toml: over the first 2 s the coupling is taken up (valve
// setting 0.1 → 1.8 bar, engine braking 0 → −10 N m), then it slides steadily on the curve's
// kinematic slip while the car slows. The slip falls with the speed, the falling μ–v branch's
// negative damping (n r F dμ/dv, dμ/dv ∝ 1/v) grows, and the linear stability analysis of the
// slipping coupling (rig_models/driveline_stability.hpp) turns unstable at ~34 rpm.
// The seed is the take-up's own ringing of the 31 Hz coupling mode (the rear differential on the
// rear half-shafts against the wheels): ~0.014 N m in the band at 2.5 s, it decays while the
// sliding is stable and grows back once the growth rate σ(t) is positive — a slow passage
// through the stability boundary. The engine's firing pulsation (2nd order, 60–80 Hz before the
// onset) is far from 31 Hz and is not this case's seed (checked below).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/shudder_detection.hpp"
#include "core/units.hpp"
#include "io/scenario.hpp"
#include "rig_models/driveline_stability.hpp"
#include "rig_models/energy_guard.hpp"
#include "rig_models/model.hpp"
#include "rig_models/recording_detection.hpp"

namespace shudder::rig_models {
namespace {

struct CoastDown {
  io::Scenario sc;
  dynamics::Recording rec;
  analysis::ShudderResult verdict;  // the run's judgement (`shudder run`): the threshold-crossing onset
};

// The shipped scenario with its slow (thermal and hydraulic) step scaled, optionally without the
// engine's firing pulsation.
CoastDown coast_down(double step_factor, bool pulsation = true) {
  CoastDown r{io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_coastdown_judder.toml"), {},
              {}};
  auto& m = std::get<DrivelineModel>(r.sc.model);
  m.settings.slow_step_s *= step_factor;
  if (!pulsation) m.params.engine_pulsation.amplitude_Nm = 0.0;
  r.rec = simulate(m, r.sc.make_clutch());
  r.verdict = judge_recording(*recording_detection(r.rec));
  return r;
}

// The criterion: halving the thermal step (10 → 5 → 2.5 ms; in the driveline it is also
// the hydraulics' and the controller's step) moves the run's onset by < 5 %, with the verdict
// unchanged. Measured (shared machine): 5.6422 / 5.6742 / 5.6829 s (+0.57 %, +0.15 %).
// What would fail: the onset as runs reported it before the threshold-crossing onset (the growth line, measured
// up from the first frames' band level) gives 3.955 / 3.959 / 4.739 s on these runs (+19.7 % at
// the second halving); a start transient above the threshold (the clamp applied as a step, as in
// driveline_takeup_judder) puts the onset at 0 whatever the step — hence the onset must come
// after the take-up.
TEST(DrivelineOnset, CoastDownOnsetChangesLessThanFivePercentWhenTheThermalStepIsHalved) {
  const CoastDown a = coast_down(1.0), b = coast_down(0.5), c = coast_down(0.25);
  std::printf("coast-down judder, thermal step 10 / 5 / 2.5 ms: onset %.4f / %.4f / %.4f s, %.2f / %.2f / %.2f Hz, "
              "%.2f / %.2f / %.2f N m\n",
              a.verdict.onset_time_s, b.verdict.onset_time_s, c.verdict.onset_time_s, a.verdict.frequency_Hz,
              b.verdict.frequency_Hz, c.verdict.frequency_Hz, a.verdict.amplitude_Nm, b.verdict.amplitude_Nm,
              c.verdict.amplitude_Nm);
  for (const CoastDown* r : {&a, &b, &c}) {
    auto old_onset = *recording_detection(r->rec);  // the figure quoted above, printed only
    old_onset.settings.onset_definition = analysis::OnsetDefinition::kGrowthLine;
    std::printf("  onset by the growth line: %.4f s\n",
                analysis::detect_shudder(old_onset.input, old_onset.settings).onset_time_s);
    EXPECT_EQ(r->verdict.verdict, analysis::Verdict::kVibration);
    // The coupling mode the linear analysis finds at the judged window's mean point (31.52 Hz);
    // the limit cycle runs 2 % below it (its slip swings onto the damping branch): 5 %.
    const auto& model = std::get<DrivelineModel>(r->sc.model);
    const auto clutch = r->sc.make_clutch();
    const double mode_Hz =
        least_damped_slipping_mode(HaldexDriveline(model.params, clutch, model.manoeuvre), clutch,
                                   recorded_operating_point(r->rec, r->verdict.oscillating_from_s,
                                                            r->verdict.oscillating_to_s))
            .frequency_Hz;
    EXPECT_NEAR(r->verdict.frequency_Hz, mode_Hz, 0.05 * mode_Hz);
    // Grown out of steady sliding, not left over from the start: after the 2 s take-up.
    EXPECT_GT(r->verdict.onset_time_s, 3.0);
    // The energy accounts close at every step (rig_models/energy_guard.hpp: 1e-6 / 1e-3).
    EXPECT_EQ(energy_balance_violation(r->rec), "");
  }
  EXPECT_LT(std::abs(b.verdict.onset_time_s / a.verdict.onset_time_s - 1.0), 0.05);
  EXPECT_LT(std::abs(c.verdict.onset_time_s / b.verdict.onset_time_s - 1.0), 0.05);
}

// The physical meaning of the onset. Along the run, the linear analysis at the recorded mean
// operating point (car speed, slip, clamp force, interface temperature, tyre forces over 50 ms)
// gives the coupling mode's growth rate σ(t); it crosses zero at t_c. The simulation's own growth
// rate is d(ln a)/dt of the amplitude a in the judder band (the detector's spectrogram, frames of
// 8 periods), which at these amplitudes (0.01–0.1 N m, linear) is fitted as a parabola in time
// from the take-up's end on: its vertex is where the simulated oscillation stops decaying, and
// its curvature is dσ/dt.
TEST(DrivelineOnset, OscillationStopsDecayingWhereTheLinearAnalysisTurnsUnstable) {
  const CoastDown r = coast_down(1.0);
  ASSERT_EQ(r.verdict.verdict, analysis::Verdict::kVibration);
  const auto& model = std::get<DrivelineModel>(r.sc.model);
  const auto clutch = r.sc.make_clutch();
  const HaldexDriveline dl(model.params, clutch, model.manoeuvre);

  // σ(t) from the end of the take-up to the onset, every 50 ms; t_c by linear interpolation.
  constexpr double kTakeUp_s = 2.0, kWindow_s = 0.05;
  double t_c = std::nan(""), previous = std::nan(""), sigma_at_onset = std::nan("");
  double sum_t = 0, sum_s = 0, sum_tt = 0, sum_ts = 0;
  int n_sigma = 0;
  for (double t = kTakeUp_s; t + kWindow_s <= r.verdict.onset_time_s; t += kWindow_s) {
    const double sigma =
        least_damped_slipping_mode(dl, clutch, recorded_operating_point(r.rec, t, t + kWindow_s)).growth_per_s;
    const double mid = t + 0.5 * kWindow_s;
    if (std::isnan(t_c) && previous < 0 && sigma >= 0) t_c = mid - kWindow_s * sigma / (sigma - previous);
    if (!std::isnan(t_c)) {  // dσ/dt after the crossing, least squares
      sum_t += mid, sum_s += sigma, sum_tt += mid * mid, sum_ts += mid * sigma;
      ++n_sigma;
    }
    previous = sigma_at_onset = sigma;
  }
  ASSERT_TRUE(std::isfinite(t_c)) << "the linear analysis never turned unstable";
  const double map_slope = (n_sigma * sum_ts - sum_t * sum_s) / (n_sigma * sum_tt - sum_t * sum_t);

  // ln a = c0 + c1 x + c2 x² (x = t − t_c) over the frames from 0.5 s after the take-up (a frame
  // is 0.26 s: clear of the ramp's end) until a tenth of the verdict's threshold.
  const auto& times = r.verdict.band_times_s;
  const auto& power = r.verdict.band_power;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  int frames = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double a = std::sqrt(2.0 * power[k]);
    if (times[k] < kTakeUp_s + 0.5) continue;
    if (a > 0.1 * r.verdict.threshold_Nm) break;
    const Eigen::Vector3d row(1.0, times[k] - t_c, (times[k] - t_c) * (times[k] - t_c));
    normal += row * row.transpose();
    rhs += row * std::log(a);
    ++frames;
  }
  ASSERT_GE(frames, 10);
  const Eigen::Vector3d c = normal.ldlt().solve(rhs);
  const double vertex = t_c - c[1] / (2.0 * c[2]), sim_slope = 2.0 * c[2];
  const auto slip_at = [&](double t) {
    const auto op = recorded_operating_point(r.rec, t - 0.5 * kWindow_s, t + 0.5 * kWindow_s);
    return units::rad_s_to_rpm(op.coupling_slip_rad_s);
  };
  std::printf("linear analysis: unstable from %.3f s (slip %.2f rpm), dsigma/dt %.3f 1/s^2; simulation: "
              "stops decaying at %.3f s (slip %.2f rpm), dsigma/dt %.3f 1/s^2 (%d frames); onset %.4f s, "
              "sigma there %.3f 1/s\n",
              t_c, slip_at(t_c), map_slope, vertex, slip_at(vertex), sim_slope, frames, r.verdict.onset_time_s,
              sigma_at_onset);
  // Measured: 5.292 s (29.11 rpm) against 5.138 s (29.51 rpm, +1.4 %), the coupling's pressure
  // and valve linearised with the motion as they are simulated. The operating point drifts
  // through the boundary at ~2 rpm/s; tolerance 2 % of the slip (0.58 rpm, ~0.3 s): a frame spans
  // 0.26 s (half a frame of drift is 0.25 rpm) and the parabola is fitted over 3.5 s of a σ(t)
  // that is not exactly linear in time.
  EXPECT_NEAR(slip_at(vertex), slip_at(t_c), 0.02 * slip_at(t_c));
  // The growth rate rises as the linear analysis says: measured 1.43 against 1.62 1/s² (15 %: the
  // fit spans 3.5 s of a σ(t) that is not linear in time; the linear analysis' own σ' is a
  // least-squares line through it).
  EXPECT_NEAR(sim_slope, map_slope, 0.15 * map_slope);
  // The onset (threshold crossing) lies after the crossing: the seed had to grow by
  // ln(threshold / a) ≈ 4.4 first. With σ = σ'(t − t_c), linear growth alone would take
  // √(2 × 4.4 / σ') ≈ 2.7 s; the simulation takes 2.3 s, because at 0.1–1 N m the oscillation's
  // low-slip half meets the steeper friction slope (∝ 1/v) and grows faster than linearly (the
  // subcritical onset of docs/driveline_stability.md). Bounds: after t_c by at least 70 % of the
  // linear delay, at most the linear delay.
  const double seed = std::exp(c[0] - c[1] * c[1] / (4.0 * c[2]));  // a at the vertex
  const double linear_delay = std::sqrt(2.0 * std::log(r.verdict.threshold_Nm / seed) / map_slope);
  std::printf("seed %.4f N m at the vertex, linear delay %.3f s, simulated %.3f s\n", seed, linear_delay,
              r.verdict.onset_time_s - t_c);
  EXPECT_GT(r.verdict.onset_time_s - t_c, 0.7 * linear_delay);
  EXPECT_LT(r.verdict.onset_time_s - t_c, linear_delay);
}

// The seed is the take-up, not the engine: without the firing pulsation the onset is the same
// to 1 % (its 50–80 Hz lie outside the 31 Hz mode's band). Measured: 5.6422 s with, 5.6415 s without.
TEST(DrivelineOnset, CoastDownSeedIsTheTakeUpNotTheFiringPulsation) {
  const CoastDown with = coast_down(1.0), without = coast_down(1.0, false);
  std::printf("onset with the firing pulsation %.4f s, without %.4f s\n", with.verdict.onset_time_s,
              without.verdict.onset_time_s);
  ASSERT_EQ(without.verdict.verdict, analysis::Verdict::kVibration);
  EXPECT_NEAR(without.verdict.onset_time_s, with.verdict.onset_time_s, 0.01 * with.verdict.onset_time_s);
}

}  // namespace
}  // namespace shudder::rig_models
