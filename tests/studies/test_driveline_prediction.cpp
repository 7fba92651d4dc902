// Take-up judder of the Haldex coupling: the linear prediction (studies/driveline_stability.hpp)
// against the simulation (rig_models/haldex_driveline.hpp), the driveline's linear prediction.
//
// Case: the tight-turn car on a legacy turn ratio ρ = 1.1 from 10 km/h, no engine torque, the
// valve holding a constant pressure p (so the coupling keeps slipping at ~20 rpm on the turn's
// kinematic slip), the schematic negative-slope fluid (μ falls above 10 rpm). The friction slope's
// negative damping grows with the clamp force, i.e. with p: the onset is a valve pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/spectrum.hpp"
#include "io/fluid_loader.hpp"
#include "io/scenario.hpp"
#include "studies/driveline_stability.hpp"
#include "rig_models/model.hpp"

namespace shudder::studies {

// The machines these studies are made of.
using namespace rig_models;

namespace {

struct TakeUp {
  DrivelineParams params;
  clutch::WetClutch clutch;
  DrivelineInputs inputs;
};

TakeUp take_up() {
  const io::Scenario sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_tight_turn.toml");
  DrivelineParams params = std::get<DrivelineModel>(sc.model).params;
  params.turn_ratio = 1.1;
  DrivelineInputs in;
  in.start_speed_km_h = 10.0;
  return {params,
          clutch::WetClutch(sc.clutch, io::load_fluid(std::string(SHUDDER_SOURCE_DIR) +
                                                      "/scenarios/fluids/schematic_negative_slope.toml")),
          in};
}

// The clamp force F realised by the preload alone (valve shut): preload torque = F n μ_nom r.
dynamics::Recording simulate_at(const TakeUp& c, double force_N, double duration_s) {
  DrivelineParams params = c.params;
  params.hydraulics.preload_torque_Nm =
      force_N * c.clutch.params().sliding_interfaces * params.nominal_friction * c.clutch.mean_radius_m();
  DrivelineInputs in = c.inputs;
  in.valve_pressure_bar = components::PiecewiseLinear({0.0}, {0.0});
  DrivelineSettings settings;
  settings.duration_s = duration_s;
  return run_driveline(params, c.clutch, in, settings);
}

// Half peak-to-peak of the coupling torque's oscillation over [t0, t1] (the 1 s moving mean
// removed by differencing against a 0.1 s mean).
double oscillation_Nm(const dynamics::Recording& rec, double t0, double t1) {
  const auto& t = rec.find("time_s")->values;
  const auto& m = rec.find("coupling_torque_Nm")->values;
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 50; i + 50 < t.size(); ++i) {
    if (t[i] < t0 || t[i] > t1) continue;
    double mean = 0;
    for (std::size_t k = i - 50; k < i + 50; ++k) mean += m[k];
    const double d = m[i] - mean / 100;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return 0.5 * (hi - lo);
}

double fft_frequency_Hz(const dynamics::Recording& rec, double t0, double f_lo, double f_hi) {
  const auto& t = rec.find("time_s")->values;
  const auto& m = rec.find("coupling_torque_Nm")->values;
  std::vector<double> x;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0) x.push_back(m[i]);
  const analysis::FftPlan plan(x.size());
  return analysis::find_peak(analysis::amplitude_spectrum(plan, x, 1000.0), f_lo, f_hi).frequency_Hz;
}

// Onset: the linear prediction's clamp force F* (the least-damped slipping mode's growth
// crosses zero at the quasi-static point) against the simulation's, found by bisection on runs
// whose oscillation (kicked by the start) either dies out (ratio of the 4–5 s to the 1–2 s
// amplitude below 1/2) or persists. Frequency: the FFT of a judder run's coupling torque at
// 1.1 F* against the linear mode's, at the quasi-static point and at the run's mean point.
TEST(DrivelinePrediction, TakeUpJudderOnsetAndFrequencyMatchTheSimulation) {
  TakeUp c = take_up();
  // The predicted system is the simulated one: the valve's setting at 0 (simulate_at), so the
  // relief valve passes the pump's flow and the pressure follows the slip as simulated.
  c.inputs.valve_pressure_bar = components::PiecewiseLinear({0.0}, {0.0});
  // The engine holds the car's speed against the coupling's scrub and the road load (so the
  // operating point stays where it was predicted): T_e s_e = M_c (s_in − s_out) + F_road r.
  {
    const HaldexDriveline dl(c.params, c.clutch, c.inputs);
    const auto op = studies::quasi_static_operating_point(dl, c.clutch, c.inputs, 1.0, 500.0);
    const double m_c = studies::coupling_thermal_feedback(dl, c.clutch, op, 30.0).coupling_torque_Nm;
    const Eigen::VectorXd s = dl.rolling_speed_ratios();
    using D = HaldexDriveline;
    const double hold = (m_c * (s[D::kCouplingIn] - s[D::kCouplingOut]) +
                         dl.road_load().force_N(op.vehicle_speed_m_s) * c.params.wheel_radius_m) /
                        s[D::kEngine];
    c.inputs.engine_torque_Nm = components::PiecewiseLinear({0.0}, {hold});
  }
  const HaldexDriveline dl(c.params, c.clutch, c.inputs);
  // The bracket holds the one crossing: stable at 50 N, unstable at 3 kN (+186 1/s). Not 5 kN:
  // with the tyres' load-proportional slip stiffness (tyre.hpp) that point is stable again
  // (−4.4 1/s at 3.0 Hz, measured) — the clamp force lowers the point's slip, which moves it
  // along the fluid's branch, and the growth is not monotonic in the force.
  const double onset = studies::onset_clamp_force_N(dl, c.clutch, c.inputs, 50.0, 3000.0);
  ASSERT_TRUE(std::isfinite(onset));
  const auto at_onset = studies::least_damped_mode(studies::driveline_stability(
      dl, c.clutch, studies::quasi_static_operating_point(dl, c.clutch, c.inputs, 1.0, onset), false));
  // The mode: the coupling's output side with the rear differential and side gears against the
  // rear wheels on the half-shafts, ~32 Hz (docs/driveline.md).
  EXPECT_NEAR(at_onset.frequency_Hz, 31.9, 0.5);

  const auto persists = [&](double force_N) {
    const auto rec = simulate_at(c, force_N, 5.0);
    return oscillation_Nm(rec, 4, 5) > 0.5 * oscillation_Nm(rec, 1, 2);
  };
  double lo = 0.8 * onset, hi = 1.2 * onset;
  ASSERT_FALSE(persists(lo));
  ASSERT_TRUE(persists(hi));
  for (int i = 0; i < 5; ++i) (persists(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  const double simulated_onset = 0.5 * (lo + hi);
  std::printf("onset: predicted %.1f N, simulated %.1f N (%+.1f %%)\n", onset, simulated_onset,
              100 * (simulated_onset / onset - 1));
  EXPECT_NEAR(simulated_onset, onset, 0.10 * onset);  // the target: within 10 %

  const double judder_N = 1.1 * onset;
  const auto rec = simulate_at(c, judder_N, 6.0);
  const double fft_Hz = fft_frequency_Hz(rec, 2.0, 10.0, 60.0);
  const double predicted_Hz =
      studies::least_damped_mode(
          studies::driveline_stability(
              dl, c.clutch, studies::quasi_static_operating_point(dl, c.clutch, c.inputs, 1.0, judder_N), false))
          .frequency_Hz;
  const double at_run_Hz =
      studies::least_damped_mode(
          studies::driveline_stability(dl, c.clutch, studies::recorded_operating_point(rec, 2.0, 6.0), false))
          .frequency_Hz;
  std::printf("frequency: FFT %.3f Hz, predicted %.3f Hz (quasi-static), %.3f Hz (run's mean point)\n", fft_Hz,
              predicted_Hz, at_run_Hz);
  // FFT bin 0.25 Hz over 4 s, interpolated (~0.02 Hz); the target is 2 %.
  EXPECT_NEAR(fft_Hz, predicted_Hz, 0.02 * predicted_Hz);
  EXPECT_NEAR(fft_Hz, at_run_Hz, 0.02 * at_run_Hz);
}

}  // namespace
}  // namespace shudder::studies
