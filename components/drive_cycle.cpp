#include "components/drive_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::components {

PiecewiseLinear::PiecewiseLinear(std::vector<double> times_s, std::vector<double> values)
    : times_s_(std::move(times_s)), values_(std::move(values)) {
  if (times_s_.empty() || times_s_.size() != values_.size())
    throw std::invalid_argument("a schedule needs equally many times and values (>= 1)");
  for (std::size_t i = 0; i < times_s_.size(); ++i) {
    if (!std::isfinite(times_s_[i]) || !std::isfinite(values_[i]))
      throw std::invalid_argument("a schedule holds a non-finite value");
    if (i > 0 && times_s_[i] <= times_s_[i - 1])
      throw std::invalid_argument("schedule times must be strictly increasing");
  }
}

double PiecewiseLinear::operator()(double t) const {
  if (t <= times_s_.front()) return values_.front();
  if (t >= times_s_.back()) return values_.back();
  const auto it = std::upper_bound(times_s_.begin(), times_s_.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - times_s_.begin());
  const double w = (t - times_s_[i - 1]) / (times_s_[i] - times_s_[i - 1]);
  return (1.0 - w) * values_[i - 1] + w * values_[i];
}

double PiecewiseLinear::max_value() const { return *std::max_element(values_.begin(), values_.end()); }
double PiecewiseLinear::min_value() const { return *std::min_element(values_.begin(), values_.end()); }

}  // namespace shudder::components
