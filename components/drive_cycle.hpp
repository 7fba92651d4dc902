#pragma once
// A drive cycle: sliding speed and normal force as piecewise-linear functions of time.
// Holds the last value after the final point and the first before t = 0. Breakpoints come from
// the scenario (e.g. Paper G Case 1: 1 -> 100 rpm in 10 s at constant force).

#include <vector>

namespace shudder::components {

class PiecewiseLinear {
 public:
  PiecewiseLinear() = default;
  /// times strictly increasing, same length as values, at least one point
  /// (std::invalid_argument otherwise).
  PiecewiseLinear(std::vector<double> times_s, std::vector<double> values);
  double operator()(double t_s) const;
  double max_value() const;
  double min_value() const;
  const std::vector<double>& times_s() const { return times_s_; }
  const std::vector<double>& values() const { return values_; }

 private:
  std::vector<double> times_s_;
  std::vector<double> values_;
};

struct DriveCycle {
  PiecewiseLinear slip_speed_rpm;  // relative speed friction disc vs separators
  PiecewiseLinear normal_force_N;  // clamp force on the pack
};

}  // namespace shudder::components
