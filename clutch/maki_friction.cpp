#include "clutch/maki_friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "clutch/axis_bracket.hpp"

namespace shudder::clutch {

double MakiSet::mu(double v) const { return c1 * std::tanh(c2 * v) + c3 * std::pow(v, 0.1) + c4; }

double MakiSet::dmu_dv(double v) const {
  const double th = std::tanh(c2 * v);
  return c1 * c2 * (1.0 - th * th) + 0.1 * c3 * std::pow(v, -0.9);
}

MakiSet shifted_row(const MakiSet& edge, double edge_temp_C, double temp_C, double slope_per_C) {
  MakiSet out = edge;
  out.c4 -= slope_per_C * (temp_C - edge_temp_C);
  return out;
}

namespace {

void require_increasing(const std::vector<double>& axis, const char* what) {
  if (axis.empty()) throw std::invalid_argument(std::string(what) + " must not be empty");
  for (std::size_t i = 0; i < axis.size(); ++i) {
    if (!std::isfinite(axis[i])) throw std::invalid_argument(std::string(what) + " holds a non-finite value");
    if (i > 0 && axis[i] <= axis[i - 1])
      throw std::invalid_argument(std::string(what) + " must be strictly increasing");
  }
}

}  // namespace

MakiFrictionMatrix::MakiFrictionMatrix(std::vector<double> loads_N, std::vector<double> temps_C,
                                       std::vector<MakiSet> sets, double min_speed_mm_s, double max_speed_mm_s)
    : loads_N_(std::move(loads_N)),
      temps_C_(std::move(temps_C)),
      sets_(std::move(sets)),
      min_speed_mm_s_(min_speed_mm_s),
      max_speed_mm_s_(max_speed_mm_s) {
  require_increasing(loads_N_, "friction matrix loads");
  require_increasing(temps_C_, "friction matrix temperatures");
  if (sets_.size() != loads_N_.size() * temps_C_.size())
    throw std::invalid_argument("friction matrix has " + std::to_string(sets_.size()) +
                                " parameter sets; loads x temperatures needs " +
                                std::to_string(loads_N_.size() * temps_C_.size()));
  for (const auto& s : sets_)
    if (!std::isfinite(s.c1) || !std::isfinite(s.c2) || !std::isfinite(s.c3) || !std::isfinite(s.c4))
      throw std::invalid_argument("friction matrix holds a non-finite coefficient");
  if (!(min_speed_mm_s_ > 0.0) || !(max_speed_mm_s_ > min_speed_mm_s_))
    throw std::invalid_argument("friction speed range must satisfy 0 < min < max");
  for (const auto& s : sets_) {
    const auto at = std::find(rates_.begin(), rates_.end(), s.c2);
    rate_of_set_.push_back(static_cast<std::size_t>(at - rates_.begin()));
    if (at == rates_.end()) rates_.push_back(s.c2);
  }
}

template <class F>
double MakiFrictionMatrix::blend(double temp_C, double load_N, F&& f) const {
  const auto [it, wt] = axis_bracket(temps_C_, temp_C);
  const auto [il, wl] = axis_bracket(loads_N_, load_N);
  const std::size_t it1 = std::min(it + 1, temps_C_.size() - 1);
  const std::size_t il1 = std::min(il + 1, loads_N_.size() - 1);
  const double lo = (1.0 - wl) * f(set(it, il)) + wl * f(set(it, il1));
  const double hi = (1.0 - wl) * f(set(it1, il)) + wl * f(set(it1, il1));
  return (1.0 - wt) * lo + wt * hi;
}

namespace {

// The blend of mu() over the four sets around (T, F), given v^0.1 and tanh(C2 v) of a set:
// one body for mu() and mu_at_load(), so both give the same numbers bit for bit. A set of
// weight zero (an operating point on an axis or clamped beyond it) is skipped, which drops
// the exact zero (1 - w) * f or w * f would have added.
template <class SetMu>
double blend_sets(std::pair<std::size_t, double> at_temp, std::pair<std::size_t, double> at_load, std::size_t n_temp,
                  std::size_t n_load, const SetMu& f) {
  const std::size_t it = at_temp.first, il = at_load.first;
  const double wt = at_temp.second, wl = at_load.second;
  const std::size_t it1 = std::min(it + 1, n_temp - 1);
  const std::size_t il1 = std::min(il + 1, n_load - 1);
  const auto row = [&](std::size_t i_temp) {
    if (wl == 0.0) return f(i_temp * n_load + il);
    if (wl == 1.0) return f(i_temp * n_load + il1);
    return (1.0 - wl) * f(i_temp * n_load + il) + wl * f(i_temp * n_load + il1);
  };
  if (wt == 0.0) return row(it);
  if (wt == 1.0) return row(it1);
  const double lo = row(it);
  const double hi = row(it1);
  return (1.0 - wt) * lo + wt * hi;
}

}  // namespace

double MakiFrictionMatrix::mu(double speed_mm_s, double temp_C, double load_N) const {
  const double v = std::clamp(std::abs(speed_mm_s), min_speed_mm_s_, max_speed_mm_s_);
  // The same numbers as blend() of MakiSet::mu, bit for bit, for less work (this is the hot
  // path of every prescribed-slip step): v^0.1 is the same for the four sets, so it is taken
  // once; a tanh whose rate equals the previous set's is reused.
  const double v_pow = std::pow(v, 0.1);
  double last_rate = std::numeric_limits<double>::quiet_NaN(), last_tanh = 0.0;
  return blend_sets(axis_bracket(temps_C_, temp_C), axis_bracket(loads_N_, load_N), temps_C_.size(), loads_N_.size(),
                    [&](std::size_t k) {
                      const MakiSet& s = sets_[k];
                      if (!(s.c2 == last_rate)) {
                        last_rate = s.c2;
                        last_tanh = std::tanh(s.c2 * v);
                      }
                      return s.c1 * last_tanh + s.c3 * v_pow + s.c4;
                    });
}

void MakiFrictionMatrix::mu_at_load(std::span<const double> speed_mm_s, std::span<const double> temp_C, double load_N,
                                    std::span<double> out, SpeedTerms& terms) const {
  // terms.values per point: [v, v^0.1, tanh(rate_0 v), tanh(rate_1 v), ...], a tanh not yet
  // taken held as NaN (taken on first use: a point uses only the rates of its four sets).
  const std::size_t n = out.size(), stride = 2 + rates_.size();
  if (!std::equal(speed_mm_s.begin(), speed_mm_s.end(), terms.speed_mm_s.begin(), terms.speed_mm_s.end())) {
    terms.speed_mm_s.assign(speed_mm_s.begin(), speed_mm_s.end());
    terms.values.assign(n * stride, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < n; ++i) {
      const double v = std::clamp(std::abs(speed_mm_s[i]), min_speed_mm_s_, max_speed_mm_s_);
      terms.values[i * stride] = v;
      terms.values[i * stride + 1] = std::pow(v, 0.1);
    }
  }
  const std::pair<std::size_t, double> at_load = axis_bracket(loads_N_, load_N);
  for (std::size_t i = 0; i < n; ++i) {
    double* p = &terms.values[i * stride];
    out[i] =
        blend_sets(axis_bracket(temps_C_, temp_C[i]), at_load, temps_C_.size(), loads_N_.size(), [&](std::size_t k) {
          const MakiSet& s = sets_[k];
          double& th = p[2 + rate_of_set_[k]];
          if (std::isnan(th)) th = std::tanh(s.c2 * p[0]);
          return s.c1 * th + s.c3 * p[1] + s.c4;
        });
  }
}

double MakiFrictionMatrix::dmu_dv_per_mm_s(double speed_mm_s, double temp_C, double load_N) const {
  const double v = std::abs(speed_mm_s);
  // Held constant outside the measured speed range: zero slope there.
  if (v < min_speed_mm_s_ || v > max_speed_mm_s_) return 0.0;
  return blend(temp_C, load_N, [v](const MakiSet& s) { return s.dmu_dv(v); });
}

}  // namespace shudder::clutch

namespace shudder::clutch {

bool MakiFrictionMatrix::speed_curve(double temp_C, double load_N, SpeedCurve& out) const {
  const auto [it, wt] = axis_bracket(temps_C_, temp_C);
  const auto [il, wl] = axis_bracket(loads_N_, load_N);
  const std::size_t it1 = std::min(it + 1, temps_C_.size() - 1);
  const std::size_t il1 = std::min(il + 1, loads_N_.size() - 1);
  out = SpeedCurve{};
  out.min_speed_mm_s = min_speed_mm_s_;
  out.max_speed_mm_s = max_speed_mm_s_;
  const auto add = [&out](const MakiSet& s, double w) {
    if (w == 0.0) return;
    out.power_weight += w * s.c3;
    out.offset += w * s.c4;
    for (std::size_t j = 0; j < out.tanh_rate.size(); ++j)
      if (out.tanh_rate[j] == s.c2) {
        out.tanh_weight[j] += w * s.c1;
        return;
      }
    out.tanh_rate.push_back(s.c2);
    out.tanh_weight.push_back(w * s.c1);
  };
  add(set(it, il), (1 - wt) * (1 - wl));
  add(set(it, il1), (1 - wt) * wl);
  add(set(it1, il), wt * (1 - wl));
  add(set(it1, il1), wt * wl);
  return true;
}

}  // namespace shudder::clutch
