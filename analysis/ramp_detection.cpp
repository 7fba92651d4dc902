#include "analysis/ramp_detection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace shudder::analysis {

const char* direction_name(RampDirection d) { return d == RampDirection::kUp ? "up" : "down"; }

namespace {

std::string fmt(const char* f, double a, double b = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

// Mean of `x` over samples whose time lies within `window_s` of time[at] on the side `dir`.
double window_mean(const std::vector<double>& t, const std::vector<double>& x, std::size_t at, int dir,
                   double window_s) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = at; i<t.size(); i = dir> 0 ? i + 1 : i - 1) {
    if (std::abs(t[i] - t[at]) > window_s && n > 0) break;
    sum += x[i];
    ++n;
    if (dir < 0 && i == 0) break;
  }
  return sum / n;
}

}  // namespace

RampSearch find_ramps(const RampRun& run, std::size_t run_index, const RampSettings& s) {
  if (!(s.smoothing_s > 0) || !(s.min_rate_rpm_s > 0) || !(s.min_span_rpm > 0) || !(s.min_duration_s >= 0) ||
      !(s.max_load_spread > 0))
    throw std::invalid_argument("ramp search settings must be positive");
  const std::size_t n = run.time_s.size();
  const auto& t = run.time_s;
  const auto& w = run.speed_rpm;
  // Label every sample by the sign of its smoothed rate: +1 up, -1 down, 0 hold.
  std::vector<int> label(n, 0);
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (t[i] - t[lo] > s.smoothing_s) ++lo;
    while (hi + 1 < n && t[hi + 1] - t[i] <= s.smoothing_s) ++hi;
    if (hi == lo) continue;
    const double rate = (w[hi] - w[lo]) / (t[hi] - t[lo]);
    label[i] = rate > s.min_rate_rpm_s ? 1 : rate < -s.min_rate_rpm_s ? -1 : 0;
  }

  RampSearch out;
  for (std::size_t i = 0; i < n;) {
    if (label[i] == 0) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < n && label[j + 1] == label[i]) ++j;
    Ramp r;
    r.run = run_index;
    r.first = i;
    r.last = j;
    r.direction = label[i] > 0 ? RampDirection::kUp : RampDirection::kDown;
    r.t_start_s = t[i];
    r.t_end_s = t[j];
    const auto [mn, mx] = std::minmax_element(w.begin() + long(i), w.begin() + long(j) + 1);
    r.min_rpm = *mn;
    r.max_rpm = *mx;
    i = j + 1;
    if (r.max_rpm - r.min_rpm < s.flicker_rpm) continue;
    double fmin = run.normal_force_N[r.first], fmax = fmin, fsum = 0.0;
    for (std::size_t k = r.first; k <= r.last; ++k) {
      fmin = std::min(fmin, run.normal_force_N[k]);
      fmax = std::max(fmax, run.normal_force_N[k]);
      fsum += run.normal_force_N[k];
    }
    r.load_N = fsum / double(r.last - r.first + 1);
    r.start_temp_C = window_mean(t, run.temp_C, r.first, +1, s.temp_window_s);
    r.end_temp_C = window_mean(t, run.temp_C, r.last, -1, s.temp_window_s);
    std::string reason;
    if (r.max_rpm - r.min_rpm < s.min_span_rpm)
      reason = fmt("spans %.3g rpm; a ramp must span at least %.3g rpm", r.max_rpm - r.min_rpm, s.min_span_rpm);
    else if (r.t_end_s - r.t_start_s < s.min_duration_s)
      reason = fmt("lasts %.3g s; a ramp must last at least %.3g s", r.t_end_s - r.t_start_s, s.min_duration_s);
    else if (!(r.load_N > 0) || (fmax - fmin) > 2.0 * s.max_load_spread * r.load_N)
      reason = fmt("load varies over %.4g N about %.4g N", fmax - fmin, r.load_N) +
               fmt("; a ramp must hold its load within ±%.3g %%", 100.0 * s.max_load_spread);
    if (reason.empty())
      out.ramps.push_back(r);
    else
      out.rejected.push_back({run_index, r.t_start_s, r.t_end_s, reason});
  }
  return out;
}

}  // namespace shudder::analysis
