#include "components/motor_ripple.hpp"

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
}

double MotorRippleTorque::revolutions(double t) const {
  // Trapezoids over the breakpoints between 0 and t; the reference is linear in between.
  const auto& ts = speed_rpm_.times_s();
  double rev = 0.0, a = 0.0;
  for (double b : ts) {
    if (b <= a) continue;
    if (b >= t) break;
    rev += 0.5 * (speed_rpm_(a) + speed_rpm_(b)) * (b - a) / 60.0;
    a = b;
  }
  return rev + 0.5 * (speed_rpm_(a) + speed_rpm_(t)) * (t - a) / 60.0;
}

double motor_ripple_at_Nm(const MotorRipple& ripple, double revolutions) {
  return ripple.amplitude_Nm * std::sin(units::kTwoPi * ripple.periods_per_rev * revolutions);
}

double MotorRippleTorque::operator()(double t) const {
  if (r_.amplitude_Nm == 0.0) return 0.0;
  return motor_ripple_at_Nm(r_, revolutions(t));
}

}  // namespace shudder::components
