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
// Bearing drag (`bearing_drag` effect, rig: equivalent mu = 0.005, thesis Method): the torque
// cell sees M_cell = M_clutch + mu_b * F * r_b * sign(Δω); it generates no heat in the discs.
//
// Torque-cell faults (`torque_sensor_gain`, `torque_sensor_offset` effects; measurement only,
// the physics is unchanged): the recorded torque is M_rec = g * M_cell + M_0 [N m]. Source:
// estimate — a mis-calibrated cell's linear error; bounds in rig_models/effect_registry.cpp.
//
// Load-cell fault (`load_sensor_gain`; measurement only): the recorded normal force is
// F_rec = g_F * F [N]. The clutch is pressed with F, so a replay of a recorded run drives the
// model with F_rec / g_F: torque and heat both follow the true force (a torque-cell gain moves
// the torque alone). Source: estimate, as for the torque cell.

#include <cmath>
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

// Friction drift (`friction_drift`; running-in or ageing of the friction pair): the interface
// torque and its heat are scaled by
//   f(s) = 1 + Δ (1 − exp(−s / s0)),    s = r_m ∫ |Δω| dt   [m], sliding distance at the mean radius,
// an exponential approach to a new level (Δ = −0.05: 5 % down). Source: estimate. The thesis
// reports that μ–v characteristics change over a clutch's life through wear of the plates and
// degradation of the fluid (Ward et al., Kugimiya et al., thesis introduction) and that the
// steady-state data are taken after run-in; the exponential approach in sliding distance is the
// simplest form that starts at the fresh value and saturates. The factor scales the whole
// interface torque (the viscous film's too, when on): the drift is not split between them.
struct FrictionDrift {
  bool enabled = false;
  double change = -0.05;     // Δ, relative change approached (estimate: a 5 % drift down)
  double distance_m = 10.0;  // s0, sliding distance of the approach (estimate)
  double factor(double sliding_m) const { return enabled ? 1.0 + change * -std::expm1(-sliding_m / distance_m) : 1.0; }
};

struct LoadCell {
  bool gain_fault = false;
  double gain = 1.0;  // g_F, recorded / true
  double reading_N(double true_N) const { return gain_fault ? gain * true_N : true_N; }
  double true_N(double reading_N) const { return gain_fault ? reading_N / gain : reading_N; }
};

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
  BearingDrag bearing_drag;
  TorqueCell torque_cell;
  LoadCell load_cell;
  FrictionDrift friction_drift;
};

/// Runs the cycle and returns the recording: signals named as docs/formats/measured_run.md (time_s, speed_rpm,
/// normal_force_N, torque_Nm, temp_C, ir_temp_C, sump_temp_C) plus internal ones, thermal
/// snapshots and summary scalars (energy balance among them).
dynamics::Recording run_prescribed_slip(const clutch::WetClutch& clutch, const DriveCycle& cycle,
                                        const PrescribedSlipSettings& settings);

}  // namespace shudder::rig_models
