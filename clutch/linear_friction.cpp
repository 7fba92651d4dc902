#include "clutch/linear_friction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::clutch {

LinearTemperatureFriction::LinearTemperatureFriction(std::vector<LinearTemperaturePoint> points)
    : points_(std::move(points)) {
  if (points_.empty()) throw std::invalid_argument("linear friction law needs at least one speed");
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const auto& p = points_[i];
    if (!std::isfinite(p.speed_mm_s) || !std::isfinite(p.alpha_per_C) || !std::isfinite(p.beta))
      throw std::invalid_argument("linear friction law holds a non-finite value");
    if (!(p.speed_mm_s > 0.0)) throw std::invalid_argument("linear friction speeds must be > 0");
    if (i > 0 && p.speed_mm_s <= points_[i - 1].speed_mm_s)
      throw std::invalid_argument("linear friction speeds must be strictly increasing");
  }
}

double LinearTemperatureFriction::mu(double speed_mm_s, double temp_C, double) const {
  const double v = std::abs(speed_mm_s);
  const auto line = [temp_C](const LinearTemperaturePoint& p) { return p.alpha_per_C * temp_C + p.beta; };
  if (v <= points_.front().speed_mm_s) return line(points_.front());
  if (v >= points_.back().speed_mm_s) return line(points_.back());
  const auto it =
      std::upper_bound(points_.begin(), points_.end(), v, [](double x, const auto& p) { return x < p.speed_mm_s; });
  const auto& hi = *it;
  const auto& lo = *(it - 1);
  const double w = std::log(v / lo.speed_mm_s) / std::log(hi.speed_mm_s / lo.speed_mm_s);
  return (1.0 - w) * line(lo) + w * line(hi);
}

double LinearTemperatureFriction::dmu_dv_per_mm_s(double speed_mm_s, double temp_C, double) const {
  const double v = std::abs(speed_mm_s);
  if (v <= points_.front().speed_mm_s || v >= points_.back().speed_mm_s) return 0.0;
  const auto it =
      std::upper_bound(points_.begin(), points_.end(), v, [](double x, const auto& p) { return x < p.speed_mm_s; });
  const auto& hi = *it;
  const auto& lo = *(it - 1);
  const double dmu = (hi.alpha_per_C - lo.alpha_per_C) * temp_C + (hi.beta - lo.beta);
  // d/dv of w(v) = ln(v/v_lo)/ln(v_hi/v_lo) is 1 / (v ln(v_hi/v_lo)).
  return dmu / (v * std::log(hi.speed_mm_s / lo.speed_mm_s));
}

}  // namespace shudder::clutch
