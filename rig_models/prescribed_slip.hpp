#pragma once
// Prescribed-slip simulation (Paper G's set-up): the sliding speed Δω(t) and the normal force
// F(t) are given; the clutch's friction and thermal field evolve together.
//
// Coupling per thermal step [t0, t1] (the multi-rate scheme of docs/architecture.md, with the fast side
// known in closed form): ring temperatures are held at their t0 values, the friction heat of
// every ring is integrated over the step by Simpson's rule (exact for the piecewise-linear
// drive within a step, up to the curvature of mu(v)), and that energy is handed to one
// backward-Euler thermal step. Recorded samples between steps interpolate linearly in time.
//
// The clutch's bearing drag and its sensors' faults: components/clutch_faults.hpp.

#include <cmath>
#include <vector>

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "components/clutch_faults.hpp"
#include "components/drive_cycle.hpp"

namespace shudder::rig_models {

/// How the thermal field is stepped (clutch/thermal_model.hpp). Backward Euler takes the ring
/// heat as the step's mean (Simpson's rule, temperatures held at the step's start): first order.
/// BDF2 takes the heat at the step's end with the film temperatures extrapolated there: second
/// order, so twice to four times the step at the same accuracy (docs/thermal_model.md).
enum class ThermalScheme { kBackwardEuler, kBdf2 };

struct PrescribedSlipSettings {
  double duration_s = 10.0;
  double thermal_step_s = 0.01;
  ThermalScheme thermal_scheme = ThermalScheme::kBackwardEuler;
  double sample_rate_Hz = 100.0;
  std::vector<double> snapshot_times_s;  // thermal-field snapshots (nearest step end)
  components::BearingDrag bearing_drag;
  components::TorqueCell torque_cell;
  components::LoadCell load_cell;
  components::FrictionDrift friction_drift;
};

/// Runs the cycle and returns the recording: signals named as docs/formats/measured_run.md (time_s, speed_rpm,
/// normal_force_N, torque_Nm, temp_C, ir_temp_C, sump_temp_C) plus internal ones, thermal
/// snapshots and summary scalars (energy balance among them).
dynamics::Recording run_prescribed_slip(const clutch::WetClutch& clutch, const components::DriveCycle& cycle,
                                        const PrescribedSlipSettings& settings);

}  // namespace shudder::rig_models
