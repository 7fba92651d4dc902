#pragma once
// Prescribed-slip simulation (Paper G's set-up): the sliding speed Δω(t) and the normal force
// F(t) are given; the clutch's friction and thermal field evolve together.
//
// Coupling per thermal step [t0, t1] (the multi-rate scheme of DESIGN.md, with the fast side
// known in closed form): ring temperatures are held at their t0 values, the friction heat of
// every ring is integrated over the step by Simpson's rule (exact for the piecewise-linear
// drive within a step, up to the curvature of mu(v)), and that energy is handed to one
// backward-Euler thermal step. Recorded samples between steps interpolate linearly in time.
//
// Bearing drag (`bearing_drag` effect, rig: equivalent mu = 0.005, thesis Method): the torque
// cell sees M_cell = M_clutch + mu_b * F * r_b * sign(Δω); it generates no heat in the discs.
//
// Torque-cell faults (`torque_sensor_gain`, `torque_sensor_offset` effects; measurement only,
// the physics is unchanged): the recorded torque is M_rec = g * M_cell + M_0 [N m]. Source:
// estimate — a mis-calibrated cell's linear error; bounds in rig_models/effect_registry.cpp.

#include <vector>

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/drive_cycle.hpp"

namespace shudder::rig_models {

struct BearingDrag {
  bool enabled = false;
  double equivalent_mu = 0.005;  // thesis: bearing losses equivalent to mu = 0.005
  double radius_m = 0.04725;     // estimate: mean radius of the modelled annulus
};

struct TorqueCell {
  bool gain_fault = false;
  double gain = 1.0;  // g, recorded / true
  bool offset_fault = false;
  double offset_Nm = 0.0;  // M_0
  double reading_Nm(double true_Nm) const {
    return (gain_fault ? gain * true_Nm : true_Nm) + (offset_fault ? offset_Nm : 0.0);
  }
};

struct PrescribedSlipSettings {
  double duration_s = 10.0;
  double thermal_step_s = 0.01;
  double sample_rate_Hz = 100.0;
  std::vector<double> snapshot_times_s;  // thermal-field snapshots (nearest step end)
  BearingDrag bearing_drag;
  TorqueCell torque_cell;
};

/// Runs the cycle and returns the recording: signals named as FORMATS.md (time_s, speed_rpm,
/// normal_force_N, torque_Nm, temp_C, ir_temp_C, sump_temp_C) plus internal ones, thermal
/// snapshots and summary scalars (energy balance among them).
dynamics::Recording run_prescribed_slip(const clutch::WetClutch& clutch, const DriveCycle& cycle,
                                        const PrescribedSlipSettings& settings);

}  // namespace shudder::rig_models
