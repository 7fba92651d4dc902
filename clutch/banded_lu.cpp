#include "clutch/banded_lu.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace shudder::clutch {

namespace {

// Both triangular sweeps on the padded vector y (`lanes` slots of padding each side, lanes a
// multiple of 4). Column updates are whole blocks of four independent `y -= a * s`, which the
// compiler turns into vector operations; built twice (AVX2 and baseline x86-64) and picked at
// load time, so the package runs on any x86-64 and uses the wider registers where they exist.
// No FMA: the multiply and the subtraction round separately in both builds (bit-identical).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void sweep(double* __restrict y, const double* __restrict lower, const double* __restrict upper,
           const double* __restrict diag, int n, int lanes) {
  // L y = x (unit lower), column by column: y[k+1..k+lanes] -= L(.., k) * y[k].
  for (int k = 0; k < n; ++k) {
    const double s = y[k];
    double* out = y + k + 1;
    const double* a = lower + static_cast<std::size_t>(k) * lanes;
    for (int t = 0; t < lanes; t += 4) {
      out[t] -= a[t] * s;
      out[t + 1] -= a[t + 1] * s;
      out[t + 2] -= a[t + 2] * s;
      out[t + 3] -= a[t + 3] * s;
    }
  }
  // U x = y, column by column from the last: x[k] = y[k] / U(k,k); y[k-lanes..k-1] -= U(.., k) x[k].
  for (int k = n - 1; k >= 0; --k) {
    y[k] /= diag[k];
    const double s = y[k];
    double* out = y + k - lanes;
    const double* a = upper + static_cast<std::size_t>(k) * lanes;
    for (int t = 0; t < lanes; t += 4) {
      out[t] -= a[t] * s;
      out[t + 1] -= a[t + 1] * s;
      out[t + 2] -= a[t + 2] * s;
      out[t + 3] -= a[t + 3] * s;
    }
  }
}

}  // namespace

BandedLu::BandedLu(int n, int half_band)
    : n_(n), b_(half_band), width_(static_cast<std::size_t>(2 * half_band + 1)) {
  if (n < 1 || half_band < 0) throw std::invalid_argument("band matrix needs n >= 1 and b >= 0");
  lanes_ = std::max(4, (half_band + 3) / 4 * 4);
  data_.assign(static_cast<std::size_t>(n) * width_, 0.0);
  lower_.assign(static_cast<std::size_t>(n) * lanes_, 0.0);
  upper_.assign(static_cast<std::size_t>(n) * lanes_, 0.0);
  diag_.assign(static_cast<std::size_t>(n), 0.0);
  padded_.assign(static_cast<std::size_t>(n + 2 * lanes_), 0.0);
}

bool BandedLu::factorize(const Eigen::SparseMatrix<double>& a) {
  if (a.rows() != n_ || a.cols() != n_) throw std::invalid_argument("band matrix size mismatch");
  std::fill(data_.begin(), data_.end(), 0.0);
  for (int k = 0; k < a.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it) {
      const int i = static_cast<int>(it.row()), j = static_cast<int>(it.col());
      if (std::abs(i - j) > b_) throw std::invalid_argument("matrix entry outside the band");
      at(i, j) += it.value();
    }
  // Right-looking elimination: column k's multipliers, then the rank-one update of the
  // trailing band, one column at a time.
  for (int k = 0; k < n_; ++k) {
    const double pivot = at(k, k);
    if (!std::isfinite(pivot) || pivot == 0.0) return false;
    const int last = std::min(n_ - 1, k + b_);
    for (int i = k + 1; i <= last; ++i) at(i, k) /= pivot;
    for (int j = k + 1; j <= last; ++j) {
      const double u = at(k, j);
      if (u == 0.0) continue;
      for (int i = k + 1; i <= last; ++i) at(i, j) -= at(i, k) * u;
    }
  }
  // The solve's padded copies (zeros where the band or the matrix ends).
  std::fill(lower_.begin(), lower_.end(), 0.0);
  std::fill(upper_.begin(), upper_.end(), 0.0);
  for (int k = 0; k < n_; ++k) {
    diag_[static_cast<std::size_t>(k)] = at(k, k);
    double* lo = &lower_[static_cast<std::size_t>(k) * lanes_];
    double* up = &upper_[static_cast<std::size_t>(k) * lanes_];
    for (int t = 0; t < b_; ++t) {
      if (k + 1 + t < n_) lo[t] = at(k + 1 + t, k);
      if (k - b_ + t >= 0) up[lanes_ - b_ + t] = at(k - b_ + t, k);
    }
  }
  return true;
}

void BandedLu::solve_in_place(Eigen::VectorXd& x) {
  // The vector sits in a scratch copy with `lanes` slots of padding at both ends, so every
  // column update has exactly `lanes` entries: near the ends the extra ones multiply zero factor
  // entries and land in the padding, which is never read.
  std::copy(x.data(), x.data() + n_, padded_.begin() + lanes_);
  double* y = padded_.data() + lanes_;
  sweep(y, lower_.data(), upper_.data(), diag_.data(), n_, lanes_);
  std::copy(y, y + n_, x.data());
}

}  // namespace shudder::clutch
