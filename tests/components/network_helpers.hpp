#pragma once
// Small builders for network tests: plain clutches and inertias in a few lines.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "studies/network_run.hpp"
#include "components/network_spec.hpp"
#include "dynamics/recording.hpp"

namespace shudder::components::test {

inline InertiaSpec inertia(const std::string& name, double j, double speed_rad_s = 0.0) {
  return {name, j, speed_rad_s};
}

/// A constant-mu clutch whose torque capacity is `kinetic_Nm` (R = 1 m, F = kinetic_Nm / mu).
inline ClutchSpec plain_clutch(const std::string& name, const std::string& a, const std::string& b, double kinetic_Nm,
                               double peak_ratio = 1.0, Signal force = Signal::constant(1.0)) {
  ClutchSpec c;
  c.name = name;
  c.a = a;
  c.b = b;
  c.law = ClutchSpec::Law::kPlain;
  c.plain.slip_rpm = {0.0};
  c.plain.mu = {0.1};
  c.plain.peak_ratio = peak_ratio;
  c.plain.geometry_factor_m = 1.0;
  c.max_force_N = kinetic_Nm / 0.1;
  c.force_signal = std::move(force);
  return c;
}

inline const std::vector<double>& channel(const dynamics::Recording& rec, const std::string& name) {
  const auto* s = rec.find(name);
  if (!s) throw std::runtime_error("no channel " + name);
  return s->values;
}

/// Largest |x − y| over a run, relative to y's range over it (infinite when the lengths differ):
/// how two runs of the same model through different paths are compared.
inline double relative_difference(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || y.empty()) return std::numeric_limits<double>::infinity();
  const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(x[i] - y[i]));
  return worst / std::max(*hi - *lo, 1e-12);
}

inline double scalar(const dynamics::Recording& rec, const std::string& name) {
  const auto* s = rec.find_scalar(name);
  if (!s) throw std::runtime_error("no scalar " + name);
  return s->value;
}

/// Time of the first sample where `flag` differs from its first value (NaN if never).
inline double first_change_s(const dynamics::Recording& rec, const std::string& flag) {
  const auto& t = channel(rec, "time_s");
  const auto& f = channel(rec, flag);
  for (std::size_t i = 1; i < f.size(); ++i)
    if ((f[i] > 0.5) != (f[0] > 0.5)) return t[i];
  return std::nan("");
}

}  // namespace shudder::components::test
