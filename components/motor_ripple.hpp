#pragma once
// Torque ripple of the rig's geared servo drive: the small, always-present physical disturbance
// from which an unstable steady sliding state starts to oscillate (without it the only seed is
// the numerical torque step at each thermal step, and the onset time follows the thermal step).
//
//   T_r(t) = A sin φ(t),   φ(t) = 2π N ∫_0^t n_ref(τ)/60 dτ                 (N m, on the drive node)
//
//   A  amplitude at the drive shaft, N m;
//   N  ripple periods per revolution of the drive shaft (1/rev); n_ref the drive speed
//      reference, rpm. The ripple is locked to the rotor angle; the speed loop holds the drive
//      on its reference to well under 1 % of a revolution, so the reference angle stands in for
//      the measured one and T_r stays a known function of time (a torque source).
//
// Values (estimates; the thesis gives neither the motor nor its ripple):
//   A = 1 N m = 0.2 % of the 500 N m rated torque. Permanent-magnet servo motors are specified
//       with cogging plus commutation ripple of roughly 0.5–2 % of rated torque; a geared drive's
//       speed loop and the gearbox's compliance filter part of it, so a fraction of a percent at
//       the disc is a conservative middle value.
//   N = 576/rev: the 6th harmonic of the electrical frequency (the dominant commutation ripple of
//       a 3-phase motor) of a 4-pole-pair motor behind the ~24:1 gearbox (lsctr_rig.hpp),
//       6 · 4 · 24 = 576; 288 Hz at 30 rpm, 1.2 kHz at the rig's 125 rpm.
// Integrator cost: the ripple is smooth, but dopri5 must resolve its period, so above the bar
// mode's frequency it shortens the step (measured: docs/rig_model.md). A = 0 removes the source.

#include <vector>

#include "components/drive_cycle.hpp"

namespace shudder::components {

struct MotorRipple {
  // On by default (the estimate, see header). The diagnosis' replay models it too: its set-point
  // recovery subtracts the ripple before inverting the speed loop (studies/speed_setpoint.hpp).
  double amplitude_Nm = 1.0;
  double periods_per_rev = 576.0;  // estimate, see header
};

/// A sin(2π N rev): the ripple at `revolutions` of the drive speed reference (no check of A, N).
double motor_ripple_at_Nm(const MotorRipple& ripple, double revolutions);

/// T_r(t) for the drive speed reference `speed_rpm` (constant before its first and after its
/// last point, as PiecewiseLinear is). Throws std::invalid_argument if amplitude < 0 or
/// periods_per_rev <= 0 (non-finite included).
class MotorRippleTorque {
 public:
  MotorRippleTorque(const MotorRipple& ripple, const PiecewiseLinear& speed_rpm);
  double operator()(double t_s) const;

 private:
  /// ∫_0^t n_ref/60 dτ, revolutions (exact for the piecewise-linear reference).
  double revolutions(double t_s) const;
  MotorRipple r_;
  PiecewiseLinear speed_rpm_;
  // From 0 s on: the reference's knots (0 first), its speed there and the revolutions up to each
  // (the integral's trapezoids summed once, so a time costs one search, not a sum over knots).
  std::vector<double> knot_t_s_, knot_rpm_, knot_rev_;
};

}  // namespace shudder::components
