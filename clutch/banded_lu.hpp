#pragma once
// LU factorisation and solve of a square band matrix, without pivoting.
//
//     A = L U,   A(i, j) = 0 for |i - j| > b;   L unit lower, U upper, both of band width b
//
// (Golub & Van Loan, Matrix Computations, 4th ed., Alg. 4.3.1 band Gaussian elimination and
// §4.3.3 band triangular solves). Cost: n·b² to factorise, 2·n·b per solve; storage n·(2b+1).
//
// Without pivoting this is backward stable only for matrices that need no pivoting; the thermal
// model's system (capacity/dt + conduction + upwind advection) is diagonally dominant by rows
// with positive diagonal (an M-matrix), for which Gaussian elimination without pivoting is
// stable with growth factor ≤ 2 (Golub & Van Loan Thm 3.4.3, Wilkinson). A zero or non-finite
// pivot is reported by factorize() returning false.
//
// Storage is column-major within the band — entry (i, k) at data[k·(2b+1) + (i - k + b)] — so
// the inner loops of the factorisation and of both solves are axpy updates on contiguous
// memory, independent of each other (no serial dot-product chain).
// After factorising, the solve's factors are copied by rows (L(m, m-b .. m-1) and
// U(m, m+b .. m+1), zeros past the matrix' ends) and both triangular solves run row by row in
// the column algorithm's operation order: the same result bit for bit, with the chain from one
// unknown to the next cut to a multiply and a subtraction (banded_lu.cpp says why).
// Neither factorize() nor solve_in_place() allocates: fit for a real-time step.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace shudder::clutch {

class BandedLu {
 public:
  BandedLu() = default;
  /// n unknowns, half band width b (entries with |i - j| <= b may be non-zero).
  BandedLu(int n, int half_band);

  /// Factorises `a` (n x n, every non-zero inside the band; entries outside it are an error).
  /// Returns false on a zero or non-finite pivot.
  bool factorize(const Eigen::SparseMatrix<double>& a);
  /// x := A⁻¹ x, with the last factorisation (x has n entries).
  void solve_in_place(Eigen::VectorXd& x);

  int size() const { return n_; }
  int half_band() const { return b_; }

 private:
  double& at(int i, int k) { return data_[static_cast<std::size_t>(k) * width_ + (i - k + b_)]; }
  double at(int i, int k) const { return data_[static_cast<std::size_t>(k) * width_ + (i - k + b_)]; }

  int n_ = 0, b_ = 0;
  std::size_t width_ = 1;
  std::vector<double> data_;
  std::vector<double> lower_;   // row m: L(m, m-b .. m-1), zeros before the matrix' start
  std::vector<double> upper_;   // row m: U(m, m+b .. m+1), zeros past the matrix' end
  std::vector<double> diag_;    // U(m, m)
  std::vector<double> padded_;  // solve scratch: the vector with b zero slots each side
};

}  // namespace shudder::clutch
