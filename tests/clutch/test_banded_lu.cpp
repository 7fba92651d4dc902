// The band LU of the thermal solve (clutch/banded_lu): solutions against Eigen's dense
// partial-pivoting LU, the band limits, and the failure report on a zero pivot.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <random>
#include <stdexcept>
#include <vector>

#include "clutch/banded_lu.hpp"

using shudder::clutch::BandedLu;

namespace {

// A random non-symmetric band matrix, diagonally dominant by rows like the thermal system
// (positive diagonal, off-diagonals of either sign here, which is harder than the M-matrix).
Eigen::SparseMatrix<double> random_band(int n, int b, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    double off = 0.0;
    for (int j = std::max(0, i - b); j <= std::min(n - 1, i + b); ++j) {
      if (j == i || u(rng) < -0.3) continue;  // leave some band entries empty
      const double v = u(rng);
      off += std::abs(v);
      t.emplace_back(i, j, v);
    }
    t.emplace_back(i, i, off + 0.5 + std::abs(u(rng)));
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace

TEST(BandedLu, SolvesLikeDensePivotingLuOnDiagonallyDominantBandMatrices) {
  std::mt19937 rng(7);
  for (const auto& [n, b] : std::vector<std::pair<int, int>>{{1, 0}, {5, 1}, {40, 3}, {240, 12}, {97, 30}}) {
    const Eigen::SparseMatrix<double> a = random_band(n, b, rng);
    BandedLu lu(n, b);
    ASSERT_TRUE(lu.factorize(a));
    const Eigen::VectorXd rhs = Eigen::VectorXd::Random(n);
    Eigen::VectorXd x = rhs;
    lu.solve_in_place(x);
    const Eigen::VectorXd ref = Eigen::MatrixXd(a).partialPivLu().solve(rhs);
    // Both are backward stable (growth <= 2 without pivoting for diagonal dominance) and the
    // matrices are well conditioned (dominance margin >= 0.5): agreement to ~n * eps.
    EXPECT_LE((x - ref).norm(), 1e-12 * ref.norm()) << "n = " << n << ", b = " << b;
    EXPECT_LE((Eigen::MatrixXd(a) * x - rhs).norm(), 1e-12 * rhs.norm());
  }
}

TEST(BandedLu, RefactorisesANewMatrixOfTheSameShape) {
  std::mt19937 rng(11);
  BandedLu lu(30, 4);
  for (int k = 0; k < 3; ++k) {
    const Eigen::SparseMatrix<double> a = random_band(30, 4, rng);
    ASSERT_TRUE(lu.factorize(a));
    Eigen::VectorXd x = Eigen::VectorXd::Ones(30);
    lu.solve_in_place(x);
    EXPECT_LE((Eigen::MatrixXd(a) * x - Eigen::VectorXd::Ones(30)).norm(), 1e-12 * std::sqrt(30.0));
  }
}

TEST(BandedLu, RejectsEntriesOutsideTheBandAndReportsAZeroPivot) {
  Eigen::SparseMatrix<double> a(4, 4);
  a.insert(0, 0) = 1.0;
  a.insert(3, 0) = 1.0;  // three below the diagonal
  BandedLu narrow(4, 2);
  EXPECT_THROW(narrow.factorize(a), std::invalid_argument);

  Eigen::SparseMatrix<double> singular(2, 2);
  singular.insert(0, 0) = 0.0;
  singular.insert(1, 1) = 1.0;
  BandedLu lu(2, 1);
  EXPECT_FALSE(lu.factorize(singular));
  EXPECT_THROW(BandedLu(0, 1), std::invalid_argument);
}

// The solve runs row by row on zero-padded rows, in the column algorithm's operation order
// (banded_lu.cpp). The result must equal, bit for bit, the plain column-oriented band
// substitution on the unpadded factors: Golub & Van Loan Alg. 4.3.2/4.3.3 written out here on
// a dense copy of A. A term taken in another order, a padding slot read from the wrong row, or
// a missed band entry at the matrix' ends changes the last bits.
TEST(BandedLu, PaddedSolveEqualsThePlainBandSubstitutionBitForBit) {
  std::mt19937 rng(3);
  // Sizes: b = 0 and 1, b = 2 (no term before the last two), b past n, odd and even n; the
  // widest unrolled sweep (24) and the generic one past it (banded_lu.cpp).
  for (const auto& [n, b] : std::vector<std::pair<int, int>>{{1, 0},
                                                             {6, 1},
                                                             {2, 2},
                                                             {3, 2},
                                                             {7, 2},
                                                             {4, 6},
                                                             {17, 4},
                                                             {240, 12},
                                                             {241, 12},
                                                             {50, 13},
                                                             {24, 24},
                                                             {80, 25},
                                                             {30, 40}}) {
    const Eigen::SparseMatrix<double> a = random_band(n, b, rng);
    // Plain band LU without pivoting, the same operation order as BandedLu::factorize.
    Eigen::MatrixXd f = Eigen::MatrixXd(a);
    for (int k = 0; k < n; ++k) {
      const int last = std::min(n - 1, k + b);
      for (int i = k + 1; i <= last; ++i) f(i, k) /= f(k, k);
      for (int j = k + 1; j <= last; ++j) {
        const double u = f(k, j);
        if (u == 0.0) continue;
        for (int i = k + 1; i <= last; ++i) f(i, j) -= f(i, k) * u;
      }
    }
    const Eigen::VectorXd rhs = Eigen::VectorXd::Random(n);
    Eigen::VectorXd ref = rhs;
    for (int k = 0; k < n; ++k)
      for (int i = k + 1; i <= std::min(n - 1, k + b); ++i) ref[i] -= f(i, k) * ref[k];
    for (int k = n - 1; k >= 0; --k) {
      ref[k] /= f(k, k);
      for (int i = std::max(0, k - b); i < k; ++i) ref[i] -= f(i, k) * ref[k];
    }
    BandedLu lu(n, b);
    ASSERT_TRUE(lu.factorize(a));
    Eigen::VectorXd x = rhs;
    lu.solve_in_place(x);
    for (int i = 0; i < n; ++i) ASSERT_EQ(x[i], ref[i]) << "n = " << n << ", b = " << b << ", i = " << i;
  }
}
