#include "analysis/breakaway.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "clutch/friction_radius.hpp"
#include "core/units.hpp"

namespace shudder::analysis {

BreakawayMeasurement measure_breakaway(const std::vector<RampRun>& runs, const FrictionConversion& conversion,
                                       const clutch::FrictionLaw& law, const BreakawaySettings& s) {
  BreakawayMeasurement out;
  const double r_mm = conversion.effective_radius_mm();
  const double mm_s_per_rpm = units::mm_s_per_rpm(r_mm);
  const double v_min = law.min_speed_mm_s();
  const double end_rpm = s.window_factor * v_min / mm_s_per_rpm;
  for (std::size_t ir = 0; ir < runs.size(); ++ir) {
    const RampRun& run = runs[ir];
    const std::size_t n = run.time_s.size();
    // mu at every sample (NaN where the force is not positive).
    std::vector<double> mu(n, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = 0; k < n; ++k)
      if (run.normal_force_N[k] > 0)
        mu[k] = clutch::mu_from_torque(std::abs(run.torque_Nm[k]), run.normal_force_N[k], r_mm / 1000.0,
                                       conversion.interfaces) -
                conversion.bearing_drag_mu;
    std::size_t k = 0;
    while (k < n) {
      // A rest phase: |speed| <= rest_rpm for at least rest_s.
      if (std::abs(run.speed_rpm[k]) > s.rest_rpm) {
        ++k;
        continue;
      }
      const std::size_t rest0 = k;
      while (k < n && std::abs(run.speed_rpm[k]) <= s.rest_rpm) ++k;
      if (k >= n || run.time_s[k - 1] - run.time_s[rest0] < s.rest_s) continue;
      // The start of the ramp: until the drive passes window_factor · v_min.
      std::size_t end = k;
      while (end < n && std::abs(run.speed_rpm[end]) < end_rpm) ++end;
      if (end >= n) break;  // the run ends before the ramp leaves the window: not a start
      BreakawayEvent ev;
      ev.run = ir;
      for (std::size_t j = rest0 + 1; j + 1 < end; ++j) {
        const double m = (mu[j - 1] + mu[j] + mu[j + 1]) / 3.0;
        if (!std::isfinite(m)) continue;
        const double v = std::max(std::abs(run.speed_rpm[j]) * mm_s_per_rpm, v_min);
        const double mk = law.mu(v, run.temp_C[j], run.normal_force_N[j]);
        if (!(mk > 0)) continue;
        if (m / mk > ev.ratio) {
          ev.ratio = m / mk;
          ev.mu_peak = m;
          ev.mu_kinetic = mk;
          ev.t_peak_s = run.time_s[j];
          ev.speed_rpm = run.speed_rpm[j];
          ev.temp_C = run.temp_C[j];
          ev.load_N = run.normal_force_N[j];
        }
      }
      if (ev.ratio > 0) out.events.push_back(ev);
      k = end;
    }
  }
  if (out.events.empty()) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "no run starts an up-ramp from rest (drive within ±%g rpm for %g s or more, then past %.3g rpm)",
                  s.rest_rpm, s.rest_s, end_rpm);
    out.not_measured = buf;
    return out;
  }
  std::vector<double> r;
  for (const auto& e : out.events) r.push_back(e.ratio);
  std::sort(r.begin(), r.end());
  out.ratio = r.size() % 2 ? r[r.size() / 2] : 0.5 * (r[r.size() / 2 - 1] + r[r.size() / 2]);
  out.min_ratio = r.front();
  out.max_ratio = r.back();
  return out;
}

}  // namespace shudder::analysis
