#pragma once
// How far a characterised friction law is from the known law the synthetic ramps were made with
// (tests/support/ramp_runs.hpp), as the characterisation tests of the sensor method
// (analysis/friction_characterisation) and of the inverse method (studies/inverse_characterisation)
// judge it: relative error |mu_fit / mu_true − 1| at the states the data hold.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "analysis/friction_characterisation.hpp"
#include "clutch/friction_law.hpp"

namespace shudder::test {

/// Max |mu_fit/mu_true − 1| over the law's rows (their temperature and load) and its node
/// speeds, including speeds no ramp reached at a row's temperature (extrapolated there).
inline double max_error_at_rows(const analysis::Characterisation& c, const clutch::FrictionLaw& truth) {
  double e = 0.0;
  for (const auto& row : c.rows)
    for (double v : c.node_speeds_mm_s)
      e = std::max(e, std::abs(c.law->mu(v, row.temp_C, row.load_N) / truth.mu(v, row.temp_C, row.load_N) - 1.0));
  return e;
}

/// Max |mu_fit/mu_true − 1| where the ramps passed: at every node speed each used ramp crosses
/// (samples within ±5 % of it), at the data model's mean interface temperature there
/// (`interface_C[run]`, sample by sample with `runs[run]`) and the run's load, skipping means
/// outside the law's rows. The law's value at a row temperature and a speed no ramp reaches at
/// that temperature (the coldest row at 100 rpm: every ramp is warmer there) is an extrapolation
/// this leaves out.
inline double max_error_where_passed(const analysis::Characterisation& c, const clutch::FrictionLaw& truth,
                                     const std::vector<analysis::RampRun>& runs,
                                     const std::vector<std::vector<double>>& interface_C) {
  double e = 0.0;
  for (const auto& ramp : c.used)
    for (std::size_t k = 0; k < c.node_rpm.size(); ++k) {
      double t = 0.0;
      int n = 0;
      for (std::size_t i = ramp.first; i <= ramp.last; ++i)
        if (std::abs(runs[ramp.run].speed_rpm[i] - c.node_rpm[k]) <= 0.05 * c.node_rpm[k]) {
          t += interface_C[ramp.run][i];
          ++n;
        }
      if (n == 0 || t / n > c.temps_C.back() || t / n < c.temps_C.front()) continue;
      const double v = c.node_speeds_mm_s[k];
      e = std::max(e, std::abs(c.law->mu(v, t / n, ramp.load_N) / truth.mu(v, t / n, ramp.load_N) - 1.0));
    }
  return e;
}

}  // namespace shudder::test
