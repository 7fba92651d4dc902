#pragma once
// Where the prescribed-slip runner's BDF2 steps end (rig_models/prescribed_slip.cpp).
//
// BDF2's second order assumes inputs that are smooth over each step. The drive cycle is
// piecewise linear: smooth between its breakpoints, and a ramp of a few milliseconds (a clamp
// force applied, a slip dropped) is a near-jump inside a 40 ms step. So the steps end on every
// breakpoint of the slip and force cycles: the segment up to the next breakpoint is cut into the
// fewest equal steps no longer than the nominal step (equal steps keep the step ratio w = 1).
// After a short step the step grows by at most 2× per step: variable-step BDF2 is zero-stable
// only for ratios w < 1 + √2 ≈ 2.41 (Grigorieff 1983; Hairer, Nørsett & Wanner, Solving ODEs I,
// §III.5), and the growth keeps every ratio ≤ 2.
//
// Measured (docs/thermal_model.md, "Abrupt cycles"): a force applied in 5 ms and a slip drop in
// 2 ms, BDF2 at 40 ms without the plan 0.45 °C off the reference, with it within the 10 ms
// backward Euler's error.

#include <vector>

namespace shudder::rig_models {

class ThermalStepPlan {
 public:
  /// breakpoints_s: the cycles' knot times (any order, repeats allowed; those outside
  /// (0, end_s) are ignored); nominal_step_s > 0; end_s: the run's duration.
  ThermalStepPlan(std::vector<double> breakpoints_s, double nominal_step_s, double end_s);

  /// The step from t_s, given the previous step's length (0 before the first step).
  double next_step_s(double t_s, double previous_step_s) const;

 private:
  std::vector<double> stops_s_;  // sorted breakpoints inside (0, end), then end
  double nominal_s_;
};

}  // namespace shudder::rig_models
