#pragma once
// The drive's speed set point, recovered from what a rig run records (drive encoder speed and
// torque cell), by inverting the rig's speed loop (rig_models/lsctr_rig.hpp).
//
// Why: a measured run carries the drive speed, not the set point. In steady sliding they agree,
// but under a rising load the PI loop lags its set point by (load rate)/ki (a ramp disturbance on
// a PI loop); in stick-slip at 0.5 rpm on the 100 Hz bar the drive crawls at ~0.12 rpm while
// stuck and races at ~1.5 rpm after breakaway. Replaying such a run with the drive speed as set
// point makes the model's loop lag a second time.
//
// Equations, on the recorded samples:
//   drive          J ω' = T_m + T_r − T_c,  T_c ≈ T_cell  (the housing's inertia term J_h ω_h' is
//                                          left out: it oscillates about zero with the bar; estimate)
//   PI loop        T_m = kp e + ki E,     E' = e,  e = ω_ref − ω
// T_r is the motor's torque ripple (motor_ripple.hpp), a known function of the set point's angle
// ∫ω_ref dt, which is integrated along as the set point is recovered. Without it in u, the loop
// inversion reads the ripple as a speed error of T_r / kp (0.13 rpm for 1 N m), at 4.8 Hz on a
// 0.5 rpm run — inside the replay's 0.05 s windows' pass band, so the replayed set point wobbles
// by a fifth of its value and the replayed stick-slip drifts from the measured one.
// With y = ki E and u = T_m = J ω' + T_cell − T_r:  τ y' + y = u,  τ = kp / ki.  Substituting
// y = v + (J/τ) ω removes the derivative from the filter:  τ v' + v = T_cell − T_r − (J/τ) ω,
// solved exactly for inputs linear between samples; then
//   e = (J ω' + T_cell − y) / kp,   ω_ref = ω + e,
// with ω' by central differences. Everything is linear, so the replay's window means of the
// result are the window means of the set point; the noise that differencing ω brings averages
// away over a window L (its share of e is J Δω / (kp L) = Δω / (ω_c L), 0.16 × Δω for the
// default 20 Hz loop and 0.05 s windows).
// Start: the rig model's own initial state — steady sliding (e = 0: the integrator carries the
// load) or at rest (E = 0).
// Limits: the motor's torque limit is not inverted (a saturated loop has no unique set point);
// a torque error δ gives a set-point error δ / kp (kp = 75 N m s/rad for the default rig:
// 1 N m → 0.13 rpm), before averaging.

#include <vector>

#include "rig_models/lsctr_rig.hpp"

namespace shudder::studies {

/// time_s strictly increasing; speed and torque of the same length (std::invalid_argument
/// otherwise). Returns the set point at the samples, rpm.
std::vector<double> estimate_speed_setpoint(const std::vector<double>& time_s,
                                            const std::vector<double>& drive_speed_rpm,
                                            const std::vector<double>& cell_torque_Nm,
                                            const rig_models::RigParams& rig);

}  // namespace shudder::studies
