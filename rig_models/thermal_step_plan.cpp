#include "rig_models/thermal_step_plan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::rig_models {

namespace {
// Times this close (relative to the nominal step) count as the same instant: a breakpoint that
// falls on a step end within round-off does not leave a sliver of a step.
constexpr double kSameInstant = 1e-9;
// The largest step ratio allowed after a shorter step (< 1 + √2, the zero-stability bound).
constexpr double kMaxGrowth = 2.0;
}  // namespace

ThermalStepPlan::ThermalStepPlan(std::vector<double> breakpoints_s, double nominal_step_s, double end_s)
    : nominal_s_(nominal_step_s) {
  if (!(nominal_step_s > 0.0) || !(end_s > 0.0))
    throw std::invalid_argument("thermal step plan: step and duration must be > 0");
  std::sort(breakpoints_s.begin(), breakpoints_s.end());
  for (double b : breakpoints_s)
    if (b > kSameInstant * nominal_s_ && b < end_s - kSameInstant * nominal_s_ &&
        (stops_s_.empty() || b - stops_s_.back() > kSameInstant * nominal_s_))
      stops_s_.push_back(b);
  stops_s_.push_back(end_s);
}

double ThermalStepPlan::next_step_s(double t_s, double previous_step_s) const {
  const double tol = kSameInstant * nominal_s_;
  const auto next = std::upper_bound(stops_s_.begin(), stops_s_.end(), t_s + tol);
  const double stop = next == stops_s_.end() ? stops_s_.back() : *next;
  const double span = stop - t_s;
  if (!(span > 0.0)) return nominal_s_;  // at or past the end: the caller's loop ends
  // The fewest equal steps no longer than the nominal one; the nominal step itself when the span
  // is a whole number of them (so a cycle whose knots sit on the step grid keeps its steps).
  const double whole = span / nominal_s_;
  const double n = std::ceil(whole - kSameInstant);
  double dt = std::abs(whole - std::round(whole)) <= kSameInstant ? nominal_s_ : span / n;
  if (span < nominal_s_ * (1.0 + kSameInstant)) dt = span;
  if (previous_step_s > 0.0) dt = std::min(dt, kMaxGrowth * previous_step_s);
  return dt;
}

}  // namespace shudder::rig_models
