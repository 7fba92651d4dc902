#include "analysis/noise_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "core/median.hpp"

namespace shudder::analysis {

double estimate_noise_sigma(const std::vector<double>& x) {
  if (x.size() < 3) return 0.0;
  std::vector<double> d2(x.size() - 2);
  for (std::size_t i = 1; i + 1 < x.size(); ++i) d2[i - 1] = x[i + 1] - 2.0 * x[i] + x[i - 1];
  const double m = core::median(d2);
  for (double& d : d2) d = std::abs(d - m);
  return 1.4826 * core::median(std::move(d2)) / std::sqrt(6.0);
}

double pooled_noise_sigma(const std::vector<const std::vector<double>*>& runs, double floor) {
  double v = 0, n = 0;
  for (const auto* x : runs) {
    const double w = static_cast<double>(x->size());
    v += w * std::pow(estimate_noise_sigma(*x), 2);
    n += w;
  }
  return std::max(std::sqrt(v / n), floor);
}

}  // namespace shudder::analysis
