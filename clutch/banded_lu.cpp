#include "clutch/banded_lu.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

namespace shudder::clutch {

namespace {

// Both triangular sweeps, row by row, on the vector y (b slots of zero padding each side).
// Row m of L y = x subtracts L(m, k) y[k] for k = m-b .. m-1 in increasing k, and row m of
// U x = y subtracts U(m, k) x[k] for k = m+b .. m+1 in decreasing k, then divides by U(m, m):
// exactly the operations, in exactly the order, that the column-oriented band substitution
// (Golub & Van Loan Alg. 4.3.2/4.3.3) applies to each entry, so the result is the same bit for
// bit (the padded terms subtract 0·0). Why rows: the column form stores each finished entry
// and reloads it for the next column, so every unknown waits for a store, a reload, a
// multiply and a subtraction in turn; here the terms of the older entries are computed while
// the previous entry is still being finished, and that entry is carried in a register, so the
// chain from one unknown to the next is one multiply and one subtraction (forward) or one
// multiply, one subtraction and the division (backward). Built for baseline x86-64, which has
// no FMA, so the multiply and the subtraction round separately, as in the reference.
// kB > 0: the half band width as a compile-time constant, so the row loops unroll completely
// (no loop counter or exit test among the terms; a 240 × 12 solve 1.90 → 1.80–1.83 µs,
// docs/performance.md); kB = 0: the width b at run time. The operations and their
// order are the same either way.
template <int kB>
void sweep(double* __restrict y, const double* __restrict lower, const double* __restrict upper,
           const double* __restrict diag, int n, int run_time_b) {
  const int b = kB > 0 ? kB : run_time_b;
  if (b == 0) {
    for (int m = 0; m < n; ++m) y[m] /= diag[m];
    return;
  }
  const std::size_t width = static_cast<std::size_t>(b);
  double prev = 0.0;  // y[m-1]: the padding's zero before the first row
  for (int m = 0; m < n; ++m) {
    const double* l = lower + static_cast<std::size_t>(m) * width;  // L(m, m-b .. m-1)
    const double* yk = y + m - b;
    double acc = y[m];
    for (int t = 0; t < b - 1; ++t) acc -= l[t] * yk[t];
    acc -= l[b - 1] * prev;
    y[m] = acc;
    prev = acc;
  }
  prev = 0.0;  // x[m+1]: the padding's zero after the last row
  for (int m = n - 1; m >= 0; --m) {
    const double* u = upper + static_cast<std::size_t>(m) * width;  // U(m, m+b .. m+1)
    const double* yk = y + m + b;
    double acc = y[m];
    for (int t = 0; t < b - 1; ++t) acc -= u[t] * yk[-t];
    acc -= u[b - 1] * prev;
    acc /= diag[m];
    y[m] = acc;
    prev = acc;
  }
}

using Sweep = void (*)(double*, const double*, const double*, const double*, int, int);

// Widths 1 … kMaxFixedWidth get their own unrolled sweep (the thermal grid's nodes per ring are
// 12 by default, Paper G Table 1); wider bands run the generic loop.
constexpr int kMaxFixedWidth = 24;

template <int... kWidths>
constexpr std::array<Sweep, sizeof...(kWidths) + 1> make_sweeps(std::integer_sequence<int, kWidths...>) {
  return {&sweep<0>, &sweep<kWidths + 1>...};
}

constexpr auto kSweeps = make_sweeps(std::make_integer_sequence<int, kMaxFixedWidth>{});

Sweep sweep_for(int b) { return b >= 1 && b <= kMaxFixedWidth ? kSweeps[static_cast<std::size_t>(b)] : &sweep<0>; }

// The right-looking elimination of factorize() on the band storage (header): column k's
// multipliers L(i, k) = A(i, k) / A(k, k), then the rank-one update A(i, j) -= L(i, k) U(k, j) of
// the trailing band, one column j at a time. Column k of the band starts at data + k·width + b,
// so A(i, k) = col_k[i - k]; each update is an axpy on two columns' contiguous, disjoint
// entries. kB > 0: the half band width as a compile-time constant, so that away from the
// matrix' end every column's update has exactly kB terms and compiles to straight-line vector
// code instead of a loop with an index computation per entry (the thermal steps' factorisations
// are a tenth of a network run with wet clutches, docs/performance.md); kB = 0: the width at
// run time. Each entry gets the same division or multiply-and-subtract, in the same order of
// columns, either way: the factors are the same bit for bit.
template <int kB>
bool eliminate(double* data, int n, int run_time_b, std::size_t width) {
  const int b = kB > 0 ? kB : run_time_b;
  for (int k = 0; k < n; ++k) {
    double* __restrict col_k = data + static_cast<std::size_t>(k) * width + b;
    const double pivot = col_k[0];
    if (!std::isfinite(pivot) || pivot == 0.0) return false;
    const int below = std::min(n - 1, k + b) - k;  // rows k+1 .. k+below
    double* __restrict l = col_k + 1;              // L(k+1 .., k)
    for (int q = 0; q < below; ++q) l[q] /= pivot;
    for (int off = 1; off <= below; ++off) {
      double* __restrict col_j = data + static_cast<std::size_t>(k + off) * width + b;
      const double u = col_j[-off];  // U(k, j)
      if (u == 0.0) continue;
      double* __restrict a = col_j - off + 1;  // A(k+1 .., j)
      if (kB > 0 && below == kB) {
        // As packets (Eigen's fixed size): a − l·u per entry, rounded as the loop below rounds.
        constexpr int kRows = kB > 0 ? kB : 1;
        Eigen::Map<Eigen::Matrix<double, kRows, 1>>(a) -= Eigen::Map<const Eigen::Matrix<double, kRows, 1>>(l) * u;
      } else {
        for (int q = 0; q < below; ++q) a[q] -= l[q] * u;
      }
    }
  }
  return true;
}

using Eliminate = bool (*)(double*, int, int, std::size_t);

template <int... kWidths>
constexpr std::array<Eliminate, sizeof...(kWidths) + 1> make_eliminations(std::integer_sequence<int, kWidths...>) {
  return {&eliminate<0>, &eliminate<kWidths + 1>...};
}

constexpr auto kEliminations = make_eliminations(std::make_integer_sequence<int, kMaxFixedWidth>{});

Eliminate elimination_for(int b) {
  return b >= 1 && b <= kMaxFixedWidth ? kEliminations[static_cast<std::size_t>(b)] : &eliminate<0>;
}

}  // namespace

BandedLu::BandedLu(int n, int half_band) : n_(n), b_(half_band), width_(static_cast<std::size_t>(2 * half_band + 1)) {
  if (n < 1 || half_band < 0) throw std::invalid_argument("band matrix needs n >= 1 and b >= 0");
  data_.assign(static_cast<std::size_t>(n) * width_, 0.0);
  lower_.assign(static_cast<std::size_t>(n) * half_band, 0.0);
  upper_.assign(static_cast<std::size_t>(n) * half_band, 0.0);
  diag_.assign(static_cast<std::size_t>(n), 0.0);
  padded_.assign(static_cast<std::size_t>(n + 2 * half_band), 0.0);
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
  if (!elimination_for(b_)(data_.data(), n_, b_, width_)) return false;
  // The solve's rows; where the band reaches past the matrix' ends they keep the zeros the
  // constructor set (those entries are never written).
  const std::size_t b = static_cast<std::size_t>(b_);
  for (int m = 0; m < n_; ++m) {
    diag_[static_cast<std::size_t>(m)] = at(m, m);
    double* lo = &lower_[static_cast<std::size_t>(m) * b];  // L(m, m-b+t)
    double* up = &upper_[static_cast<std::size_t>(m) * b];  // U(m, m+b-t)
    for (int t = 0; t < b_; ++t) {
      if (m - b_ + t >= 0) lo[t] = at(m, m - b_ + t);
      if (m + b_ - t < n_) up[t] = at(m, m + b_ - t);
    }
  }
  return true;
}

void BandedLu::solve_in_place(Eigen::VectorXd& x) {
  // The vector sits in a scratch copy with b slots of zero padding at both ends, so every row
  // has exactly b terms: near the ends the extra ones multiply zero factor entries by the
  // padding's zeros, which the sweeps never write.
  std::copy(x.data(), x.data() + n_, padded_.begin() + b_);
  double* y = padded_.data() + b_;
  sweep_for(b_)(y, lower_.data(), upper_.data(), diag_.data(), n_, b_);
  std::copy(y, y + n_, x.data());
}

}  // namespace shudder::clutch
