#pragma once
// Where a value sits on a sorted axis, for the friction tables' interpolation (Mäki matrix and
// table law share the rule, so the two laws clamp and blend identically).
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace shudder::clutch {

/// Index i and weight w such that x lies between axis[i] and axis[i+1] (w = 0 at axis[i]),
/// after clamping x to the axis ends. A single-point axis gives (0, 0).
inline std::pair<std::size_t, double> axis_bracket(const std::vector<double>& axis, double x) {
  if (axis.size() == 1 || x <= axis.front()) return {0, 0.0};
  if (x >= axis.back()) return {axis.size() - 2, 1.0};
  const auto it = std::upper_bound(axis.begin(), axis.end(), x);
  const std::size_t i = static_cast<std::size_t>(it - axis.begin()) - 1;
  return {i, (x - axis[i]) / (axis[i + 1] - axis[i])};
}

}  // namespace shudder::clutch
