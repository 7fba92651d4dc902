#pragma once
// median(v): the middle value of v (the mean of the two middle values for an even count), NaN
// for an empty v. O(n) by selection (std::nth_element), so v is taken by value and reordered.
#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace shudder::core {

inline double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  // After the selection the lower middle value is the largest of the elements before mid.
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

}  // namespace shudder::core
