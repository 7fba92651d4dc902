#pragma once
// A clutch's bearing drag and the faults of the sensors that measure it: what a measured run
// sees besides the friction interface. Each part is switched by its effect; the effects' names
// and bounds are in rig_models/effect_registry.cpp.
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

namespace shudder::components {

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

}  // namespace shudder::components
