#include "studies/transient_oscillation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace shudder::studies {

namespace {

// r = x − (centred moving mean over one period) where the window fits; `half` its half width.
std::vector<double> residual(std::span<const double> t, std::span<const double> x, double f, std::size_t& half) {
  const std::size_t n = std::min(t.size(), x.size());
  half = 0;
  if (n < 4 || !(f > 0)) return {};
  const double dt = (t[n - 1] - t[0]) / static_cast<double>(n - 1);
  half = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.5 / (f * dt))));
  if (2 * half + 1 > n) return {};
  std::vector<double> sum(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) sum[i + 1] = sum[i] + x[i];
  std::vector<double> r;
  for (std::size_t i = half; i + half < n; ++i)
    r.push_back(x[i] - (sum[i + half + 1] - sum[i - half]) / static_cast<double>(2 * half + 1));
  return r;
}

}  // namespace

std::vector<double> period_amplitudes_from_end(std::span<const double> t, std::span<const double> x, double f) {
  std::size_t half = 0;
  const auto r = residual(t, x, f, half);
  std::vector<double> out;
  const std::size_t period = 2 * half;
  if (period == 0) return out;
  for (std::size_t end = r.size(); end >= period; end -= period) {
    const auto [lo, hi] = std::minmax_element(r.begin() + static_cast<std::ptrdiff_t>(end - period),
                                              r.begin() + static_cast<std::ptrdiff_t>(end));
    out.push_back(0.5 * (*hi - *lo));
  }
  return out;
}

int oscillation_swings(std::span<const double> t, std::span<const double> x, double f, double level) {
  if (!(level > 0)) return 0;
  std::size_t half = 0;
  int swings = 0, side = 0;
  for (double r : residual(t, x, f, half)) {
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

}  // namespace shudder::studies
