// Prediction against simulation: the linear stability of steady sliding on the
// rig (studies/rig_stability) predicts where a slow speed ramp starts to shudder and at what
// frequency. The nonlinear rig simulation (rig_models::run_rig, thermal model on) gives the
// simulated values, and they must agree.
//
// Cases: 3 SCHEMATIC fluids x 3 bars (175, 300, 450 Hz). The ramp scenarios are
// scenarios/rig_ramp_{peak10,peak20,thermal}.toml: 5 -> 45 rpm over 8 s at 15 kN, from 40 degC.
// Each fluid (scripts/make_schematic_ramp_fluids.py) has a friction maximum. Above it the
// isothermal slope falls linearly with speed; in the thermal fluid that slope's zero also moves
// 0.83 rpm lower per K of warming.
//
// Predicted onset speed v_p: the slip speed where the rig's largest OSCILLATORY real part
// crosses zero. That real part comes from rig_stability: steady sliding at speed v, the ramp's
// force, and every ring at the run's mean interface temperature at the time the ramp reaches v
// (the isothermal slope of docs/physics.md §6). v_p is found by a scan along the ramp in 0.25 rpm steps
// for the first sign change, then bisection on speed. It uses the oscillatory mode, not the
// overall margin, which the drive loop's slow real mode can lead (rig_stability.hpp) and which
// is not what shudders. The predicted frequency is that mode's damped frequency at v_p.
//
// Simulated onset speed v_s: the slip (mean over one period) at the detector's onset time,
// with the onset defined for ramps. That is OnsetDefinition::kGrowthRateZero,
// analysis/shudder_detection.hpp, kGrowthRateZero: a parabola is fitted to the band power (dB) of the free
// exponential growth, and its vertex is the instant the growth rate crossed zero. Along a slow
// ramp the growth rate rises linearly through zero, so the log amplitude is that parabola. Its
// vertex is what linear theory calls the onset, and the test compares it with v_p. Two other
// onsets are not physically honest here, for these reasons:
//   * the default definition (kGrowthLine) extrapolates a secant of the convex growth down to the start
//     level. That level is where the growth emerges from the floor, not where it began, so the
//     result depends on the floor: -6 % to +33 % here (late where the floor is flat, early where
//     it rises);
//   * the minimum of the band power is not the onset either. The floor is not noise: the
//     thermal coupling's steps (every 10 ms) give small torque steps, and these force the bar
//     mode. As the damping falls toward zero, that forced floor rises: by ~40 dB on the 300 Hz
//     bar (the third harmonic of the 100 Hz steps) and ~20 dB on the 450 Hz bar, so its minimum
//     comes far too early. On the 175 Hz bar the floor stays flat, and its minimum falls
//     anywhere in it.
// The simulated frequency is the detector's dominant frequency: the interpolated FFT peak over
// the oscillating part.
//
// Tolerances: onset speed 10 % and frequency 2 % (the targets). Measured: onset within
// 2 % and frequency within 0.5 %, per case in the test's recorded properties.
// Also checked, against the linear theory rather than the targets:
//   * the rate dσ/dt at which the growth rate rises. The parabola's curvature is compared with
//     the least-squares slope of the predicted margin against time, from the predicted onset to
//     the end of the fitted frames. The tolerance is 15 %, because the tabulated law's ln-v
//     interpolation makes the margin a sawtooth about its trend (±1 1/s). Measured within 5 %.
//   * for the thermal fluid, the interface warming matters. Predicting with the start
//     temperature held moves the onset by more than 5 %, and the simulation sides with the
//     prediction at the run's temperature.
//
// Item 5's torsion-bar sweep (scenarios/sweep_torsion_bar.toml) is checked end to end through
// the CLI at the bottom.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/shudder_detection.hpp"
#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "io/hdf5_sweep.hpp"
#include "io/scenario.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "studies/rig_stability.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/models.hpp"
#include "tests/support/record_property.hpp"

namespace {

using shudder::analysis::DetectionSettings;
using shudder::analysis::OnsetDefinition;
using shudder::analysis::ShudderDetector;
using shudder::analysis::ShudderResult;
using shudder::analysis::Verdict;
using shudder::dynamics::Recording;
using shudder::io::Scenario;

using shudder::test::record;

Scenario scenario(const std::string& name) {
  return shudder::io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/" + name);
}

// Linear interpolation of a recorded signal at time t (uniform samples from time_s[0]).
double at_time(const Recording& rec, const char* name, double t) {
  const auto& ts = rec.find("time_s")->values;
  const auto& v = rec.find(name)->values;
  const double u = std::clamp((t - ts.front()) / (ts[1] - ts[0]), 0.0, static_cast<double>(ts.size() - 1));
  const auto i = std::min(static_cast<std::size_t>(u), ts.size() - 2);
  return v[i] + (u - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

// The predicted onset along a linear speed ramp, with the run's interface temperature.
class RampPrediction {
 public:
  RampPrediction(const Scenario& sc, const shudder::clutch::WetClutch& clutch, const Recording& rec)
      : sc_(sc), clutch_(clutch), rec_(rec) {
    const auto& ts = shudder::test::rig_model(sc).cycle.slip_speed_rpm.times_s();
    const auto& vs = shudder::test::rig_model(sc).cycle.slip_speed_rpm.values();
    if (ts.size() != 2 || !(vs[1] > vs[0])) throw std::invalid_argument("expected one rising speed ramp");
    t0_ = ts[0];
    v0_ = vs[0];
    v1_ = vs[1];
    rate_ = (vs[1] - vs[0]) / (ts[1] - ts[0]);
  }

  double time_at(double v) const { return t0_ + (v - v0_) / rate_; }
  double speed_at(double t) const { return shudder::test::rig_model(sc_).cycle.slip_speed_rpm(t); }
  double temp_at_speed(double v) const { return at_time(rec_, "interface_mean_temp_C", time_at(v)); }

  // The oscillatory mode at speed v of the ramp; the temperature is the run's, or `temp_C`.
  shudder::analysis::StabilityPoint point(double v, double temp_C = std::nan("")) const {
    const double T = std::isnan(temp_C) ? temp_at_speed(v) : temp_C;
    return shudder::studies::rig_stability(shudder::test::rig_model(sc_).params, clutch_,
                                           shudder::test::rig_model(sc_).cycle.normal_force_N(time_at(v)), v, T);
  }
  double margin(double v, double temp_C = std::nan("")) const { return point(v, temp_C).oscillatory_margin_per_s; }

  // First upward zero crossing of the oscillatory margin along the ramp: a scan in 0.25 rpm
  // steps, then bisection on speed to 1e-6 rpm. NaN if the margin never turns positive.
  double onset_rpm(double temp_C = std::nan("")) const {
    double lo = v0_;
    if (margin(lo, temp_C) > 0.0) return v0_;
    for (double v = v0_ + 0.25; v <= v1_ + 1e-9; v += 0.25) {
      if (margin(v, temp_C) > 0.0) {
        double hi = v;
        while (hi - lo > 1e-6) {
          const double mid = 0.5 * (lo + hi);
          (margin(mid, temp_C) > 0.0 ? hi : lo) = mid;
        }
        return 0.5 * (lo + hi);
      }
      lo = v;
    }
    return std::nan("");
  }

  // Least-squares slope of the margin against time over [t_a, t_b], 1/s².
  double margin_rate_per_s2(double t_a, double t_b) const {
    double st = 0, sm = 0, stt = 0, stm = 0;
    int n = 0;
    for (double t = t_a; t <= t_b + 1e-12; t += 0.01, ++n) {
      const double m = margin(speed_at(t));
      st += t;
      sm += m;
      stt += t * t;
      stm += t * m;
    }
    return (n * stm - st * sm) / (n * stt - st * st);
  }

 private:
  const Scenario& sc_;
  const shudder::clutch::WetClutch& clutch_;
  const Recording& rec_;
  double t0_ = 0, v0_ = 0, v1_ = 0, rate_ = 0;
};

struct CaseResult {
  double predicted_rpm = 0, simulated_rpm = 0, predicted_Hz = 0, simulated_Hz = 0;
  double isothermal_rpm = 0;  // predicted with the start temperature held
};

// Runs one fluid's ramp on one bar and checks the targets.
CaseResult compare(const std::string& scenario_name, double bar_Hz) {
  Scenario sc = scenario(scenario_name);
  shudder::test::rig_model(sc).params.bar_natural_frequency_Hz = bar_Hz;
  // The prediction is the linear stability of the autonomous rig; the motor's torque ripple
  // is a forcing whose frequency (9.6 Hz per rpm) crosses the 175 Hz bar at 18 rpm
  // on the ramp and adds a resonant floor to the band the onset is fitted in: switched off.
  shudder::test::rig_model(sc).params.motor_ripple.amplitude_Nm = 0.0;
  const auto clutch = sc.make_clutch();
  const Recording rec =
      shudder::rig_models::run_rig(shudder::test::rig_model(sc).params, clutch, shudder::test::rig_model(sc).cycle,
                                   shudder::test::rig_model(sc).settings);

  DetectionSettings settings;
  settings.onset_definition = OnsetDefinition::kGrowthRateZero;
  const ShudderDetector detector(settings);
  const ShudderResult r = detector.detect(rec);
  const ShudderResult line = ShudderDetector().detect(rec);  // default onset, for the record

  const RampPrediction pred(sc, clutch, rec);
  CaseResult c;
  c.predicted_rpm = pred.onset_rpm();
  c.isothermal_rpm = pred.onset_rpm(sc.clutch.start_temp_C);
  const auto at_onset = pred.point(c.predicted_rpm);
  c.predicted_Hz = at_onset.oscillatory_frequency_Hz;
  c.simulated_rpm = r.at_onset.slip_rpm;
  c.simulated_Hz = r.frequency_Hz;

  // dσ/dt: the parabola's vertex is at the onset and its slope at the end of the fitted frames
  // (the oscillating part's start) is σ there, so compare with the mean rate of the predicted
  // margin over that span (least squares, which also averages the sawtooth).
  const double predicted_rate = pred.margin_rate_per_s2(pred.time_at(c.predicted_rpm), r.oscillating_from_s);

  // "rig_ramp_peak10.toml" on 175 Hz -> "peak10_175Hz"
  const std::size_t prefix = std::string("rig_ramp_").size(), suffix = std::string(".toml").size();
  const std::string key = scenario_name.substr(prefix, scenario_name.size() - prefix - suffix) + "_" +
                          std::to_string(static_cast<int>(bar_Hz)) + "Hz";
  record(key,
         "onset predicted %.3f rpm (%.2f degC at it; %.3f rpm with 40 degC held), simulated %.3f rpm at %.3f s "
         "(%+.2f %%; default onset %.3f rpm, %+.1f %%); frequency predicted %.3f Hz, simulated %.3f Hz (%+.3f %%); "
         "dsigma/dt fitted %.2f, predicted %.2f 1/s2 (to %.3f s); %s, amplitude %.1f N m",
         c.predicted_rpm, pred.temp_at_speed(c.predicted_rpm), c.isothermal_rpm, c.simulated_rpm, r.onset_time_s,
         100.0 * (c.simulated_rpm / c.predicted_rpm - 1.0), line.at_onset.slip_rpm,
         100.0 * (line.at_onset.slip_rpm / c.predicted_rpm - 1.0), c.predicted_Hz, c.simulated_Hz,
         100.0 * (c.simulated_Hz / c.predicted_Hz - 1.0), r.growth_acceleration_per_s2, predicted_rate,
         r.oscillating_from_s, std::string(to_string(r.verdict)).c_str(), r.amplitude_Nm);

  EXPECT_TRUE(std::isfinite(c.predicted_rpm)) << key << ": the prediction never turns unstable";
  // The fluids' rising branch below the maximum and their flat top bound the vibration: the
  // slip stays above zero.
  EXPECT_EQ(r.verdict, Verdict::kVibration) << key;
  EXPECT_TRUE(std::isfinite(r.growth_acceleration_per_s2)) << key << ": the growth-rate-zero onset did not apply";
  EXPECT_NEAR(c.simulated_rpm / c.predicted_rpm, 1.0, 0.10) << key;  // target: 10 %
  EXPECT_NEAR(c.simulated_Hz / c.predicted_Hz, 1.0, 0.02) << key;    // target: 2 %
  EXPECT_NEAR(r.growth_acceleration_per_s2 / predicted_rate, 1.0, 0.15) << key;
  return c;
}

void compare_fluid(const std::string& scenario_name, std::vector<CaseResult>* out = nullptr) {
  for (double bar_Hz : {175.0, 300.0, 450.0}) {
    SCOPED_TRACE(scenario_name + " on the " + std::to_string(static_cast<int>(bar_Hz)) + " Hz bar");
    const CaseResult c = compare(scenario_name, bar_Hz);
    if (out) out->push_back(c);
  }
}

}  // namespace

// Friction maximum at 10 rpm with a gentle fall above it: onsets at ~13, ~16 and ~19 rpm.
TEST(PredictionVsSimulation, RampPeak10OnsetSpeedAndFrequencyOnThreeBars) { compare_fluid("rig_ramp_peak10.toml"); }

// Maximum at 20 rpm with a steeper fall: onsets close above it (~21-25 rpm).
TEST(PredictionVsSimulation, RampPeak20OnsetSpeedAndFrequencyOnThreeBars) { compare_fluid("rig_ramp_peak20.toml"); }

// Maximum at 16 rpm at 40 degC, moving 0.83 rpm lower per K: the warming along the ramp
// (+2-4 K by the onset) brings the onset earlier, so the prediction must use the run's
// interface temperature. With 40 degC held it is off by more than 5 %, and the simulation sides
// with the run-temperature prediction.
TEST(PredictionVsSimulation, RampThermalOnsetFollowsTheInterfaceTemperature) {
  std::vector<CaseResult> cases;
  compare_fluid("rig_ramp_thermal.toml", &cases);
  ASSERT_EQ(cases.size(), 3u);
  for (const auto& c : cases) {
    EXPECT_GT(c.isothermal_rpm / c.predicted_rpm - 1.0, 0.05);
    EXPECT_LT(std::abs(c.simulated_rpm - c.predicted_rpm), std::abs(c.simulated_rpm - c.isothermal_rpm));
  }
}

// Item 5: `shudder sweep scenarios/sweep_torsion_bar.toml --set ...=100:500:100`. With the bar's
// damping ratio fixed, its damping 2ζ√(kJ_h) grows with the bar frequency, so the fixed negative
// slope of the scenario (-0.89 N m s/rad) beats it on soft bars only. critical_bar puts the
// boundary at 355.2 Hz (the scenario's header). So 100-300 Hz are predicted unstable and shudder
// at the bar's frequency, while 400-500 Hz are predicted stable and do not. The simulated
// boundary, between the last bar that shudders and the first that does not, brackets the
// predicted one.
TEST(PredictionVsSimulation, SweepTorsionBarHasBothVerdictsSplitWhereCriticalBarPredicts) {
  using namespace shudder::test;
  const Scenario sc = scenario("sweep_torsion_bar.toml");
  const auto clutch = sc.make_clutch();
  const double force = shudder::test::rig_model(sc).cycle.normal_force_N(0.0),
               speed = shudder::test::rig_model(sc).cycle.slip_speed_rpm(0.0);
  const auto crit =
      shudder::studies::critical_bar(shudder::test::rig_model(sc).params, clutch, force, speed, sc.clutch.start_temp_C);
  EXPECT_NEAR(crit.frequency_Hz, 355.2, 0.1);  // as documented in the scenario's header
  // Soft side unstable, stiff side stable.
  auto soft = shudder::test::rig_model(sc).params, stiff = shudder::test::rig_model(sc).params;
  soft.bar_natural_frequency_Hz = 100.0;
  stiff.bar_natural_frequency_Hz = 500.0;
  EXPECT_GT(shudder::studies::rig_stability(soft, clutch, force, speed, sc.clutch.start_temp_C).margin_per_s, 0.0);
  EXPECT_LT(shudder::studies::rig_stability(stiff, clutch, force, speed, sc.clutch.start_temp_C).margin_per_s, 0.0);

  const auto dir = scratch_dir("prediction_sweep_torsion_bar");
  const auto r = run_cli("sweep '" + source_path("scenarios/sweep_torsion_bar.toml") +
                             "' --set rig.torsion_bar.natural_frequency_Hz=100:500:100 --jobs 2 --quiet -o sw.h5",
                         dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto t = shudder::io::read_sweep_table((dir / "sw.h5").string());
  const auto* bar = t.find("rig.torsion_bar.natural_frequency_Hz");
  ASSERT_NE(bar, nullptr);
  ASSERT_EQ(bar->values.size(), 5u);
  double last_shudder = 0.0, first_quiet = 1e9;
  int shudders = 0, quiet = 0;
  for (std::size_t k = 0; k < 5; ++k) {
    const double f = bar->values[k];
    const bool predicted_stable = t.find("predicted_stable")->values[k] != 0.0;
    const std::string& verdict = t.text_column[k];
    record("sweep_" + std::to_string(static_cast<int>(f)) + "Hz",
           "predicted %s (margin %.3f 1/s, %.2f Hz), simulated %s (%.2f Hz, %.2f N m)",
           predicted_stable ? "stable" : "unstable", t.find("predicted_margin_per_s")->values[k],
           t.find("predicted_frequency_Hz")->values[k], verdict.c_str(), t.find("simulated_frequency_Hz")->values[k],
           t.find("amplitude_Nm")->values[k]);
    EXPECT_EQ(predicted_stable, f > crit.frequency_Hz) << f;
    EXPECT_EQ(verdict == "none", predicted_stable) << f << " Hz: " << verdict;
    if (verdict == "none") {
      ++quiet;
      first_quiet = std::min(first_quiet, f);
    } else {
      ++shudders;
      last_shudder = std::max(last_shudder, f);
      EXPECT_EQ(verdict, "vibration") << f;
      EXPECT_NEAR(t.find("simulated_frequency_Hz")->values[k] / t.find("predicted_frequency_Hz")->values[k], 1.0, 0.02)
          << f;
    }
  }
  EXPECT_GT(shudders, 0);
  EXPECT_GT(quiet, 0);
  EXPECT_LT(last_shudder, first_quiet);  // one boundary, soft side shudders
  EXPECT_GT(crit.frequency_Hz, last_shudder);
  EXPECT_LT(crit.frequency_Hz, first_quiet);
}
