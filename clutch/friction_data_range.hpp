#pragma once
// How much of a run used the friction law outside its data. A law is
// defined by data over a speed range, a temperature range and a load range
// (FrictionLaw::min/max_speed_mm_s, temp_range_C, load_range_N); outside them it holds or
// extrapolates (the Mäki matrix clamps speed to 6–590 mm/s, load to its first/last load and
// temperature to its end rows, Paper G). A run that goes there is still computed, but its
// friction is not measured friction: the run must say so.
//
// Tally, per slow (thermal) step of duration dt, with the step's slip, the rings' interface
// temperatures and the clamp force:
//   speed below   some sliding ring's local speed |Δω| r_i < min speed (only while sliding:
//                 slowest ring above 0.01 mm/s)
//   speed above   some ring's |Δω| r_i > max speed
//   temp below/above   some ring's interface temperature outside the temperature range
//   load below/above   the clamp force outside the load range
// Each adds dt to its time; `outside_s` counts a step once however many ranges it leaves.
// The extremes seen are kept for the message. Every runner (prescribed slip, and every network's
// wet clutches through the multi-rate coupling) feeds one tally per clutch.

#include <Eigen/Dense>
#include <limits>

#include "clutch/friction_law.hpp"

namespace shudder::clutch {

struct FrictionDataRange {
  explicit FrictionDataRange(const FrictionLaw& law);

  /// One step: `slip_rad_s` the (mean) slip over it, `ring_radius_m` and `ring_temp_C` (n_r).
  void add(double dt_s, double slip_rad_s, const Eigen::VectorXd& ring_radius_m, const Eigen::VectorXd& ring_temp_C,
           double load_N);

  // The law's data ranges.
  double speed_lo_mm_s, speed_hi_mm_s, temp_lo_C, temp_hi_C, load_lo_N, load_hi_N;
  // Time, s.
  double total_s = 0.0, outside_s = 0.0;
  double speed_below_s = 0.0, speed_above_s = 0.0, temp_below_s = 0.0, temp_above_s = 0.0;
  double load_below_s = 0.0, load_above_s = 0.0;
  // Extremes seen while sliding (speed) or at all (temperature, load).
  static constexpr double kSlidingThreshold_mm_s = 0.01;
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double min_speed_mm_s = kInf, max_speed_mm_s = 0.0;
  double min_temp_C = kInf, max_temp_C = -kInf, min_load_N = kInf, max_load_N = -kInf;
};

}  // namespace shudder::clutch
