#include "analysis/temperature_surface.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::analysis {

namespace {

// Index k and weight w of x between xs[k] and xs[k+1] (x clamped to the axis).
std::pair<std::size_t, double> locate(const std::vector<double>& xs, double x) {
  if (x <= xs.front()) return {0, 0.0};
  if (x >= xs.back()) return {xs.size() - 2, 1.0};
  const std::size_t k = std::size_t(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin()) - 1;
  return {k, (x - xs[k]) / (xs[k + 1] - xs[k])};
}

// Adds lambda · (second difference along x)² for every line of the grid: unknown (m, o) is at
// m·stride + o·other_stride.
void add_second_differences(Eigen::MatrixXd& a, const std::vector<double>& x, std::size_t stride, std::size_t n_other,
                            std::size_t other_stride, double lambda) {
  for (std::size_t m = 1; m + 1 < x.size(); ++m) {
    const double h0 = x[m] - x[m - 1], h1 = x[m + 1] - x[m], hm = 0.5 * (h0 + h1);
    const double c[3] = {hm / h0, -hm / h0 - hm / h1, hm / h1};
    for (std::size_t o = 0; o < n_other; ++o)
      for (std::size_t p = 0; p < 3; ++p)
        for (std::size_t q = 0; q < 3; ++q)
          a(long((m - 1 + p) * stride + o * other_stride), long((m - 1 + q) * stride + o * other_stride)) +=
              lambda * c[p] * c[q];
  }
}

void check_axis(const std::vector<double>& xs, const char* what) {
  if (xs.size() < 2) throw std::invalid_argument(std::string("a temperature surface needs 2 or more ") + what);
  for (std::size_t k = 1; k < xs.size(); ++k)
    if (!(xs[k] > xs[k - 1]))
      throw std::invalid_argument(std::string("temperature surface: ") + what + " not increasing");
}

}  // namespace

std::vector<double> temperature_knots(std::vector<double> rows_C, double min_C, double max_C) {
  std::sort(rows_C.begin(), rows_C.end());
  rows_C.erase(std::unique(rows_C.begin(), rows_C.end()), rows_C.end());  // equal rows: h = 0 never ends
  double h = 10.0;                                                        // one row: the spacing of Paper G's matrix
  if (rows_C.size() > 1) {
    h = rows_C[1] - rows_C[0];
    for (std::size_t k = 2; k < rows_C.size(); ++k) h = std::min(h, rows_C[k] - rows_C[k - 1]);
  }
  std::vector<double> knots;
  for (double t = rows_C.front(); t > min_C;) knots.insert(knots.begin(), t -= h);
  knots.insert(knots.end(), rows_C.begin(), rows_C.end());
  for (double t = rows_C.back(); t < max_C;) knots.push_back(t += h);
  return knots;
}

TemperatureSurface::TemperatureSurface(std::vector<double> speed_knots_mm_s, std::vector<double> temp_knots_C,
                                       const std::vector<SurfaceSample>& samples)
    : speeds_(std::move(speed_knots_mm_s)), temps_(std::move(temp_knots_C)) {
  check_axis(speeds_, "speed knots");
  check_axis(temps_, "temperature knots");
  if (samples.size() < 4) throw std::invalid_argument("a temperature surface needs at least 4 samples");
  for (double v : speeds_) lnv_.push_back(std::log(v));
  const std::vector<double>& lnv = lnv_;
  const std::size_t nv = speeds_.size(), nt = temps_.size();
  const long k = long(nv * nt);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(k);
  for (const SurfaceSample& s : samples) {
    const auto [it, wt] = locate(temps_, s.temp_C);
    const auto [iv, wv] = locate(lnv, std::log(s.v_mm_s));
    const long idx[4] = {long(it * nv + iv), long(it * nv + iv + 1), long((it + 1) * nv + iv),
                         long((it + 1) * nv + iv + 1)};
    const double w[4] = {(1 - wt) * (1 - wv), (1 - wt) * wv, wt * (1 - wv), wt * wv};
    for (int p = 0; p < 4; ++p) {
      b(idx[p]) += w[p] * s.mu;
      for (int q = 0; q < 4; ++q) a(idx[p], idx[q]) += w[p] * w[q];
    }
  }
  // Second differences along each axis (file comment). Unequal spacings: the divided
  // difference times the mean spacing², so the penalty is in units of mu on either axis.
  const double lambda = kSmoothing * double(samples.size()) / double(k);
  add_second_differences(a, temps_, nv, nv, 1, lambda);
  add_second_differences(a, lnv, 1, nt, nv, lambda);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
  const Eigen::VectorXd theta = ldlt.solve(b);
  if (ldlt.info() != Eigen::Success || !theta.allFinite())
    throw std::runtime_error("the temperature surface's least-squares system is singular");
  theta_.assign(theta.data(), theta.data() + k);
  double ss = 0.0;
  for (const SurfaceSample& s : samples) ss += std::pow((*this)(s.v_mm_s, s.temp_C) - s.mu, 2);
  rms_ = std::sqrt(ss / double(samples.size()));
}

double TemperatureSurface::operator()(double v_mm_s, double temp_C) const {
  const std::size_t nv = speeds_.size();
  const auto [it, wt] = locate(temps_, temp_C);
  // Plain copies: C++17 lambdas may not capture structured bindings (clang rejects it).
  const auto speed_cell = locate(lnv_, std::log(v_mm_s));
  const std::size_t j = speed_cell.first;
  const double u = speed_cell.second;
  const auto at = [&](std::size_t i) { return (1 - u) * theta_[i * nv + j] + u * theta_[i * nv + j + 1]; };
  return (1 - wt) * at(it) + wt * at(it + 1);
}

}  // namespace shudder::analysis
