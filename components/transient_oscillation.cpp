#include "components/transient_oscillation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace shudder::components {

int oscillation_swings(std::span<const double> t, std::span<const double> x, double f, double level) {
  const std::size_t n = std::min(t.size(), x.size());
  if (n < 4 || !(f > 0) || !(level > 0)) return 0;
  const double dt = (t[n - 1] - t[0]) / static_cast<double>(n - 1);
  const std::size_t half = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.5 / (f * dt))));
  if (2 * half + 1 > n) return 0;
  // Prefix sums for the centred moving mean.
  std::vector<double> sum(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) sum[i + 1] = sum[i] + x[i];
  int swings = 0, side = 0;
  for (std::size_t i = half; i + half < n; ++i) {
    const double mean = (sum[i + half + 1] - sum[i - half]) / static_cast<double>(2 * half + 1);
    const double r = x[i] - mean;
    const int now = r > level ? 1 : (r < -level ? -1 : 0);
    if (now != 0 && now != side) {
      if (side != 0) ++swings;
      side = now;
    }
  }
  return swings;
}

int stick_onsets(std::span<const double> stuck) {
  int n = 0;
  for (std::size_t i = 1; i < stuck.size(); ++i)
    if (stuck[i] > 0.5 && stuck[i - 1] < 0.5) ++n;
  return n;
}

}  // namespace shudder::components
