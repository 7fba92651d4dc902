#include "components/motor_ripple.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace shudder::components {

MotorRippleTorque::MotorRippleTorque(const MotorRipple& ripple, const PiecewiseLinear& speed_rpm)
    : r_(ripple), speed_rpm_(speed_rpm) {
  if (!(r_.amplitude_Nm >= 0) || !std::isfinite(r_.amplitude_Nm))
    throw std::invalid_argument("motor torque ripple amplitude must be >= 0 N m");
  if (!(r_.periods_per_rev > 0) || !std::isfinite(r_.periods_per_rev))
    throw std::invalid_argument("motor torque ripple periods per revolution must be > 0");
  double a = 0.0, rev = 0.0;
  knot_t_s_ = {0.0};
  knot_rpm_ = {speed_rpm_(0.0)};
  knot_rev_ = {0.0};
  for (double b : speed_rpm_.times_s()) {
    if (b <= a) continue;
    rev += 0.5 * (speed_rpm_(a) + speed_rpm_(b)) * (b - a) / 60.0;
    a = b;
    knot_t_s_.push_back(b);
    knot_rpm_.push_back(speed_rpm_(b));
    knot_rev_.push_back(rev);
  }
}

double MotorRippleTorque::revolutions(double t) const {
  // The trapezoids up to the last knot before t, then the one from there to t; the reference
  // is linear in between.
  const auto after = std::lower_bound(knot_t_s_.begin(), knot_t_s_.end(), t);
  const auto i = static_cast<std::size_t>(after == knot_t_s_.begin() ? 0 : after - knot_t_s_.begin() - 1);
  return knot_rev_[i] + 0.5 * (knot_rpm_[i] + speed_rpm_(t)) * (t - knot_t_s_[i]) / 60.0;
}

double motor_ripple_at_Nm(const MotorRipple& ripple, double revolutions) {
  return ripple.amplitude_Nm * std::sin(units::kTwoPi * ripple.periods_per_rev * revolutions);
}

double MotorRippleTorque::operator()(double t) const {
  if (r_.amplitude_Nm == 0.0) return 0.0;
  return motor_ripple_at_Nm(r_, revolutions(t));
}

}  // namespace shudder::components
