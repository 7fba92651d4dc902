#include "analysis/residual_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shudder::analysis {

std::vector<std::pair<std::size_t, std::size_t>> residual_blocks(const std::vector<double>& t) {
  std::vector<std::pair<std::size_t, std::size_t>> blocks;
  const std::size_t n = t.size();
  if (n == 0) return blocks;
  const double duration = t.back() - t.front();
  const double dt = n > 1 ? duration / static_cast<double>(n - 1) : 0.0;
  const double block_s = std::max(std::clamp(duration / 80.0, 0.05, 1.0), 5.0 * dt);
  std::size_t begin = 0;
  while (begin < n) {
    std::size_t end = begin;
    const double t_end = t[begin] + block_s;
    while (end < n && t[end] < t_end - 1e-9 * block_s) ++end;
    end = std::max(end, begin + 1);
    // A short tail joins the previous block instead of making a noisy one of its own.
    if (!blocks.empty() && n - begin < 3) {
      blocks.back().second = n;
      break;
    }
    blocks.emplace_back(begin, end);
    begin = end;
  }
  return blocks;
}

std::vector<double> block_means(const std::vector<double>& x,
                                const std::vector<std::pair<std::size_t, std::size_t>>& blocks) {
  std::vector<double> m;
  m.reserve(blocks.size());
  for (const auto& [b, e] : blocks) {
    double s = 0.0;
    for (std::size_t i = b; i < e; ++i) s += x[i];
    m.push_back(s / static_cast<double>(e - b));
  }
  return m;
}

BlockFeatures block_features(const std::vector<double>& t, const std::vector<double>& speed_rpm,
                             const std::vector<double>& temp_C, const std::vector<double>& force_N,
                             const std::vector<std::pair<std::size_t, std::size_t>>& blocks) {
  const std::size_t nb = blocks.size();
  const auto tm = block_means(t, blocks);
  std::vector<double> abs_speed(speed_rpm.size());
  for (std::size_t i = 0; i < speed_rpm.size(); ++i) abs_speed[i] = std::abs(speed_rpm[i]);
  const auto speed = block_means(abs_speed, blocks);
  const auto temp = block_means(temp_C, blocks);
  const auto force = block_means(force_N, blocks);

  // Central differences of block means (one-sided at the ends).
  const auto rate = [&](const std::vector<double>& v) {
    std::vector<double> r(nb, 0.0);
    if (nb < 2) return r;
    for (std::size_t b = 0; b < nb; ++b) {
      const std::size_t lo = b == 0 ? 0 : b - 1, hi = b + 1 == nb ? b : b + 1;
      r[b] = (v[hi] - v[lo]) / (tm[hi] - tm[lo]);
    }
    return r;
  };
  const auto temp_rate = rate(temp);
  const auto speed_rate = rate(speed);
  double max_rate = 0.0;
  for (double r : speed_rate) max_rate = std::max(max_rate, std::abs(r));
  std::vector<double> direction(nb, 0.0);
  for (std::size_t b = 0; b < nb; ++b)
    if (std::abs(speed_rate[b]) > 0.05 * max_rate) direction[b] = speed_rate[b] > 0 ? 1.0 : -1.0;

  const double max_speed = speed.empty() ? 0.0 : *std::max_element(speed.begin(), speed.end());
  std::vector<double> dwell(nb, 0.0);
  for (std::size_t b = 0; b < nb; ++b) {
    const auto low = [&](std::size_t i) { return speed[i] < 0.1 * max_speed; };
    if (low(b) && b > 0 && low(b - 1)) dwell[b] = dwell[b - 1] + (tm[b] - tm[b - 1]);
  }
  std::vector<double> rise(nb);
  for (std::size_t b = 0; b < nb; ++b) rise[b] = temp[b] - temp.front();

  BlockFeatures f;
  f.names = {"time",          "temperature_rise",       "temperature_rate",
             "sliding_speed", "speed_change_direction", "low_speed_dwell",
             "normal_force"};
  f.values = {tm, rise, temp_rate, speed, direction, dwell, force};
  return f;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n < 3) return 0.0;
  const double ma = std::accumulate(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(n), 0.0) / n;
  const double mb = std::accumulate(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0, scale_a = 0, scale_b = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
    scale_a = std::max(scale_a, std::abs(a[i]));
    scale_b = std::max(scale_b, std::abs(b[i]));
  }
  // A feature that is constant up to round-off has no correlation with anything.
  const double tiny = 1e-24 * static_cast<double>(n);
  if (saa <= tiny * scale_a * scale_a || sbb <= tiny * scale_b * scale_b || saa == 0 || sbb == 0) return 0.0;
  return sab / std::sqrt(saa * sbb);
}

std::vector<Segment> residual_segments(const std::vector<double>& residual, double sigma,
                                       const std::vector<std::pair<std::size_t, std::size_t>>& blocks) {
  std::vector<Segment> out;
  const auto means = block_means(residual, blocks);
  int run_sign = 0;
  std::size_t run_first = 0, run_blocks = 0;
  const auto close = [&](std::size_t end_block) {
    if (run_sign != 0 && run_blocks >= 2) {
      Segment s;
      s.first_sample = blocks[run_first].first;
      s.end_sample = blocks[end_block - 1].second;
      double sum = 0.0;
      for (std::size_t i = s.first_sample; i < s.end_sample; ++i) sum += residual[i];
      s.mean = sum / static_cast<double>(s.end_sample - s.first_sample);
      out.push_back(s);
    }
    run_sign = 0;
    run_blocks = 0;
  };
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const double n = static_cast<double>(blocks[b].second - blocks[b].first);
    const double threshold = std::max(3.0 * sigma / std::sqrt(n), 0.5 * sigma);
    const int sign = means[b] > threshold ? 1 : (means[b] < -threshold ? -1 : 0);
    if (sign != run_sign) {
      close(b);
      if (sign != 0) {
        run_sign = sign;
        run_first = b;
      }
    }
    if (sign != 0) ++run_blocks;
  }
  close(blocks.size());
  return out;
}

std::vector<std::pair<std::string, double>> rank_features(const std::vector<double>& r, const BlockFeatures& features) {
  std::vector<std::pair<std::string, double>> ranked;
  for (std::size_t f = 0; f < features.names.size(); ++f)
    ranked.emplace_back(features.names[f], pearson(r, features.values[f]));
  double sum = 0.0, sq = 0.0;
  for (double x : r) {
    sum += x;
    sq += x * x;
  }
  if (!r.empty() && sq > 0) {
    const double offset = std::abs(sum / r.size()) / std::sqrt(sq / r.size());
    // Mostly constant: |mean| carries > 90 % of the rms, i.e. the spread is < 44 % of it.
    if (offset > 0.9) ranked.emplace_back("offset", offset);
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  return ranked;
}

}  // namespace shudder::analysis
