#pragma once
// The least-norm least-squares solution x = B^+ c of a symmetric positive semi-definite system,
// singular where contacts are redundant (a face's four corners: three would hold it). The friction
// solve needs it for every active set it tries, so it must be cheap (a complete orthogonal
// decomposition, two pivoted QRs, is not: docs/design/psd-pseudo-inverse.md). Here P^T B P =
// G G^T by a Cholesky factorisation with symmetric pivoting that stops at B's rank r (LAPACK's
// dpstrf; Higham, "Cholesky factorization of a positive semidefinite matrix", 1990), G = [G1; G2]
// with G1 r x r lower triangular. B's null space is spanned by N = P [-G1^-T G2^T; I]; a right-
// hand side is projected off it, solved with G1 G1^T (the basic solution), and the solution
// projected off it again: the least-norm one. The projections cost (k - r)-sized solves, k - r
// being the redundant rows, mostly few: no Householder reflections. The kernels are plain loops
// over G^T's columns (G's rows, contiguous): the systems have 2-60 rows, where Eigen's blocked
// triangular and product kernels spend more setting up than computing. Where the redundant rows
// are at least as many as the rank (a box pushed through a pile: 54 sticking rows of rank 11),
// the projections cost more than the answer itself;
// there B^+ = P G (G^T G)^-2 G^T P^T (G has full column rank), one r x r Cholesky factor instead of
// the projections' (k - r) x (k - r) one: 2kr + 2r^2 a column, not 4(k - r)r + 2(k - r)^2 + r^2.
#include <Eigen/Dense>

#include <vector>

namespace wysiwyf::haptics {

class PsdPseudoInverse {
  static constexpr Eigen::Index kManyColumns = 8;  // half_solve: Eigen's matrix kernels from here

 public:
  // B: symmetric positive semi-definite (both triangles are read). A pivot below threshold
  // times B's largest diagonal entry ends the factorisation: the rest of B is round-off.
  void compute(const Eigen::MatrixXd& B, double threshold);
  Eigen::Index rank() const { return rank_; }
  // x = B^+ c, column by column (c: k rows; x a vector or a matrix, and may be c).
  template <typename Rhs, typename Out>
  void solve(const Eigen::MatrixBase<Rhs>& c, Eigen::PlainObjectBase<Out>& x) const;
  // Z (r x n) with C^T B^+ C = Z^T Z for C (k x n): Z = G1^-1 (P^T C projected off N)'s first r
  // rows: one projection and one triangular solve where B^+ C takes two of each (through G^T G:
  // Z = (G^T G)^-1 G^T P^T C).
  template <typename Rhs>
  void half_solve(const Eigen::MatrixBase<Rhs>& C, Eigen::MatrixXd& Z) const;

 private:
  // On one column y (k entries, in the factor's order):
  void project_off_null_space(double* y) const;  // y less its part in B's null space
  // The same on every column of permuted_ (Eigen's blocked kernels: worth setting up for many
  // columns, such as the friction solve's Ant_T), and the forward solve.
  void project_off_null_space_all() const;
  void forward_all() const;
  void forward(double* y) const;         // y's first r entries := G1^-1 y
  void solve_permuted(double* y) const;  // the first r := (G1 G1^T)^-1 y, the rest 0
  // Through G^T G (in_range_): z (r) := (G^T G)^-1 G^T y, and y := G (G^T G)^-1 z.
  void range_half(const double* y, double* z) const;
  void range_solve(double* y) const;
  void range_half_all(Eigen::MatrixXd& Z) const;
  template <typename Rhs>
  void permute_in(const Eigen::MatrixBase<Rhs>& c) const;

  Eigen::MatrixXd H_;  // G^T: H_(l, i) = G(i, l), for l < rank_ (column i: G's row i)
  Eigen::VectorXd diagonal_;
  std::vector<Eigen::Index> order_;  // row i of G is B's row order_[i]
  Eigen::Index rank_ = 0;
  Eigen::MatrixXd M_;      // G1^-T G2^T (r x (k - r))
  Eigen::MatrixXd gram_;   // the Cholesky factor (upper) of N^T N = I + M^T M; in_range_: of G^T G
  bool in_range_ = false;  // solved through G^T G (H_'s first r rows, below G1^T's diagonal zeroed)
  mutable Eigen::MatrixXd permuted_, t_matrix_;
  mutable Eigen::VectorXd t_;
};

template <typename Rhs>
void PsdPseudoInverse::permute_in(const Eigen::MatrixBase<Rhs>& c) const {
  const auto k = static_cast<Eigen::Index>(order_.size());
  permuted_.resize(k, c.cols());
  for (Eigen::Index i = 0; i < k; ++i) permuted_.row(i) = c.row(order_[static_cast<std::size_t>(i)]);
}

template <typename Rhs, typename Out>
void PsdPseudoInverse::solve(const Eigen::MatrixBase<Rhs>& c, Eigen::PlainObjectBase<Out>& x) const {
  const auto k = static_cast<Eigen::Index>(order_.size());
  permute_in(c);  // (c is read here only: x may be c)
  for (Eigen::Index j = 0; j < permuted_.cols(); ++j) {
    double* y = permuted_.col(j).data();
    if (in_range_) {
      range_solve(y);
      continue;
    }
    project_off_null_space(y);
    solve_permuted(y);
    project_off_null_space(y);
  }
  x.resize(k, c.cols());
  for (Eigen::Index i = 0; i < k; ++i) x.row(order_[static_cast<std::size_t>(i)]) = permuted_.row(i);
}

template <typename Rhs>
void PsdPseudoInverse::half_solve(const Eigen::MatrixBase<Rhs>& C, Eigen::MatrixXd& Z) const {
  permute_in(C);
  if (in_range_) {
    range_half_all(Z);
    return;
  }
  if (permuted_.cols() >= kManyColumns) {
    project_off_null_space_all();
    forward_all();
  } else {
    for (Eigen::Index j = 0; j < permuted_.cols(); ++j) {
      double* y = permuted_.col(j).data();
      project_off_null_space(y);
      forward(y);
    }
  }
  Z = permuted_.topRows(rank_);
}

}  // namespace wysiwyf::haptics
