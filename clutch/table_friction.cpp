#include "clutch/table_friction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "clutch/axis_bracket.hpp"

namespace shudder::clutch {

namespace {

void require_axis(const std::vector<double>& axis, const char* what) {
  if (axis.empty()) throw std::invalid_argument(std::string("friction table ") + what + " must not be empty");
  for (std::size_t i = 0; i < axis.size(); ++i) {
    if (!std::isfinite(axis[i]))
      throw std::invalid_argument(std::string("friction table ") + what + " holds a non-finite value");
    if (i > 0 && !(axis[i] > axis[i - 1]))
      throw std::invalid_argument(std::string("friction table ") + what + " must be strictly increasing");
  }
}

}  // namespace

TableFriction::TableFriction(std::vector<double> speeds_mm_s, std::vector<double> temps_C, std::vector<double> loads_N,
                             std::vector<double> mu)
    : speeds_(std::move(speeds_mm_s)), temps_(std::move(temps_C)), loads_(std::move(loads_N)), mu_(std::move(mu)) {
  require_axis(speeds_, "speeds");
  require_axis(temps_, "temperatures");
  require_axis(loads_, "loads");
  if (!(speeds_.front() > 0.0)) throw std::invalid_argument("friction table speeds must be > 0");
  if (mu_.size() != speeds_.size() * temps_.size() * loads_.size())
    throw std::invalid_argument("friction table has " + std::to_string(mu_.size()) +
                                " values; temperatures x loads x speeds needs " +
                                std::to_string(speeds_.size() * temps_.size() * loads_.size()));
  for (const double m : mu_)
    if (!std::isfinite(m)) throw std::invalid_argument("friction table holds a non-finite value");
}

template <class F>
double TableFriction::blend(double temp_C, double load_N, F&& f) const {
  const auto [it, wt] = axis_bracket(temps_, temp_C);
  const auto [il, wl] = axis_bracket(loads_, load_N);
  const std::size_t it1 = std::min(it + 1, temps_.size() - 1);
  const std::size_t il1 = std::min(il + 1, loads_.size() - 1);
  const double lo = (1.0 - wl) * f(it, il) + wl * f(it, il1);
  const double hi = (1.0 - wl) * f(it1, il) + wl * f(it1, il1);
  return (1.0 - wt) * lo + wt * hi;
}

double TableFriction::mu(double speed_mm_s, double temp_C, double load_N) const {
  const double v = std::clamp(std::abs(speed_mm_s), speeds_.front(), speeds_.back());
  if (speeds_.size() == 1) return blend(temp_C, load_N, [&](auto a, auto b) { return value(a, b, 0); });
  std::size_t k = static_cast<std::size_t>(std::upper_bound(speeds_.begin(), speeds_.end(), v) - speeds_.begin());
  k = std::clamp<std::size_t>(k, 1, speeds_.size() - 1) - 1;
  const double w = std::log(v / speeds_[k]) / std::log(speeds_[k + 1] / speeds_[k]);
  return blend(temp_C, load_N,
               [&](std::size_t a, std::size_t b) { return (1.0 - w) * value(a, b, k) + w * value(a, b, k + 1); });
}

double TableFriction::dmu_dv_per_mm_s(double speed_mm_s, double temp_C, double load_N) const {
  const double v = std::abs(speed_mm_s);
  if (speeds_.size() == 1 || v < speeds_.front() || v > speeds_.back()) return 0.0;
  std::size_t k = static_cast<std::size_t>(std::upper_bound(speeds_.begin(), speeds_.end(), v) - speeds_.begin());
  k = std::clamp<std::size_t>(k, 1, speeds_.size() - 1) - 1;
  // d/dv of w(v) = ln(v/v_k)/ln(v_k+1/v_k) is 1 / (v ln(v_k+1/v_k)).
  const double dw = 1.0 / (v * std::log(speeds_[k + 1] / speeds_[k]));
  return blend(temp_C, load_N,
               [&](std::size_t a, std::size_t b) { return (value(a, b, k + 1) - value(a, b, k)) * dw; });
}

}  // namespace shudder::clutch
