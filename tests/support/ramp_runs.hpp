#pragma once
// Synthetic measured ramp runs for the characterisation tests and benchmark: a known fluid
// driven through the project's prescribed-slip clutch and thermal model (Paper G thermal
// defaults), written as a measured run with the rig's sensor noise (io/measurement_csv).
//
//   Paper D cycle (docs/physics.md §4): N0 = 1 rpm for 5 s, ramp to 100 rpm in t_ramp, hold 2 s,
//                                  ramp down to 1 rpm in t_ramp, hold 3 s.
//   Paper E cycle: five times (1 rpm for 3 s, then 1 -> 100 rpm in 10 s).
#include <functional>
#include <string>
#include <vector>

#include "analysis/ramp_detection.hpp"
#include "clutch/wet_clutch.hpp"
#include "io/measurement_csv.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::test {

inline components::DriveCycle paper_d_cycle(double load_N, double t_ramp_s = 10.0) {
  const double t1 = 5.0, t2 = t1 + t_ramp_s, t3 = t2 + 2.0, t4 = t3 + t_ramp_s, t5 = t4 + 3.0;
  return {components::PiecewiseLinear({0.0, t1, t2, t3, t4, t5}, {1.0, 1.0, 100.0, 100.0, 1.0, 1.0}),
          components::PiecewiseLinear({0.0}, {load_N})};
}

inline components::DriveCycle paper_e_cycle(double load_N, int ramps = 5) {
  std::vector<double> t, w;
  for (int k = 0; k < ramps; ++k) {
    const double t0 = 13.0 * k;
    t.insert(t.end(), {t0, t0 + 3.0, t0 + 13.0 - 1e-3});
    w.insert(w.end(), {1.0, 1.0, 100.0});
  }
  t.push_back(13.0 * ramps);
  w.push_back(1.0);
  return {components::PiecewiseLinear(t, w), components::PiecewiseLinear({0.0}, {load_N})};
}

/// Another thermal model than the one the characterisations replay or compensate with, as a
/// `vary` for simulated_ramp_run: twice the radial cells (40 against 20), an oil flow through the
/// contact that grows with slip (fraction e 0.010 + a 0.002 (Δω + 1): 0.4 % more flow per 2 rad/s;
/// the shipped calibration has a = 0) and a thermocouple lagging the disc by 0.5 s.
inline void other_thermal_model(clutch::WetClutchParams& p) {
  p.thermal.radial_cells = 40;
  p.thermal.oil_flow.a = 0.002;
  p.thermal.oil_flow.e = 0.010;
  p.thermal.temperature_sensor_lag = true;
  p.thermal.sensor_time_constant_s = 0.5;
}

/// One simulated run of `cycle` from `start_temp_C` (discs and sump), sampled at `rate_Hz` with
/// sensor noise (seed), as the characterisation reads it. `temp_channel` may also name a model
/// signal the measured run does not carry; `interface_mean_C` (if given) gets the model's
/// area-mean interface temperature at the same samples (where the ramps passed); `vary` changes the clutch and thermal
/// parameters (another thermal model than the one the characterisation is judged by). `temp_channel` may name a model
/// signal the measured run does not carry (e.g. interface_mean_temp_C: the temperature a
/// sensor would need to read for exact compensation), taken noise-free from the recording.
inline analysis::RampRun simulated_ramp_run(const clutch::Fluid& fluid, const components::DriveCycle& cycle,
                                            double start_temp_C, unsigned seed, double rate_Hz = 100.0,
                                            const std::string& temp_channel = "temp_C",
                                            const std::function<void(clutch::WetClutchParams&)>& vary = {},
                                            std::vector<double>* interface_mean_C = nullptr) {
  clutch::WetClutchParams p;  // Paper G thermal defaults, one sliding interface
  if (vary) vary(p);
  p.start_temp_C = start_temp_C;
  p.sump_start_temp_C = start_temp_C;
  const clutch::WetClutch clutch(p, fluid);
  rig_models::PrescribedSlipSettings s;
  s.duration_s = cycle.slip_speed_rpm.times_s().back();
  s.thermal_step_s = 0.02;
  s.sample_rate_Hz = rate_Hz;
  const dynamics::Recording rec = rig_models::run_prescribed_slip(clutch, cycle, s);
  io::MeasurementOptions mo;
  mo.noise = true;
  mo.seed = seed;
  const io::MeasuredRun m = io::make_measurement("synthetic_" + std::to_string(seed), rec, mo);
  const std::vector<double>* temp = m.column(temp_channel);
  if (!temp) temp = &rec.find(temp_channel)->values;  // same samples: no resampling asked for
  if (interface_mean_C) *interface_mean_C = rec.find("interface_mean_temp_C")->values;
  return {m.path, m.required("time_s"), m.required("speed_rpm"), m.required("normal_force_N"), m.required("torque_Nm"),
          *temp};
}

}  // namespace shudder::test
