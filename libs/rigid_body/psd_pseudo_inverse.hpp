#pragma once
// The least-norm least-squares solution x = B^+ c of a symmetric positive semi-definite system,
// singular where contacts are redundant (a face's four corners: three would hold it). The friction
// solve needs it for every active set it tries: a complete orthogonal decomposition (a column-
// pivoted QR of all k rows, then one more of R) was 36 % of a 5-cube stack's step. Here P^T B P =
// G G^T by a Cholesky factorisation with symmetric pivoting that stops at B's rank r (LAPACK's
// dpstrf; Higham, "Cholesky factorization of a positive semidefinite matrix", 1990), G = [G1; G2]
// with G1 r x r lower triangular. B's null space is spanned by N = P [-G1^-T G2^T; I]; a right-
// hand side is projected off it, solved with G1 G1^T (the basic solution), and the solution
// projected off it again: the least-norm one. The projections cost (k - r)-sized solves, k - r
// being the redundant rows, mostly few: no Householder reflections.
#include <Eigen/Dense>

#include <vector>

namespace wysiwyf::haptics {

class PsdPseudoInverse {
 public:
  // B: symmetric positive semi-definite (both triangles are read). A pivot below threshold
  // times B's largest diagonal entry ends the factorisation: the rest of B is round-off.
  void compute(const Eigen::MatrixXd& B, double threshold);
  Eigen::Index rank() const { return rank_; }
  // x = B^+ c, column by column (c: k rows, evaluated: an expression would be evaluated again for
  // each row; x a vector or a matrix, and may be c).
  template <typename Rhs, typename Out>
  void solve(const Eigen::MatrixBase<Rhs>& c, Eigen::PlainObjectBase<Out>& x) const;
  // Z (r x n) with C^T B^+ C = Z^T Z for C (k x n): Z = G1^-1 (P^T C projected off N)'s first r
  // rows: one projection and one triangular solve where B^+ C takes two of each.
  template <typename Rhs>
  void half_solve(const Eigen::MatrixBase<Rhs>& C, Eigen::MatrixXd& Z) const;

 private:
  // y (k x n, in the factor's order) less its part in B's null space; t: workspace (a vector
  // where y is one: Eigen's matrix kernels cost hundreds of instructions to set up for a column).
  template <typename Y, typename T>
  void project_off_null_space(Y&& y, T& t) const;
  template <typename Y>
  void solve_permuted(Y&& y) const;
  template <typename Rhs>
  void permute_in(const Eigen::MatrixBase<Rhs>& c) const;

  Eigen::MatrixXd work_, G_;
  Eigen::VectorXd diagonal_;
  std::vector<Eigen::Index> order_;  // row i of G is B's row order_[i]
  Eigen::Index rank_ = 0;
  Eigen::MatrixXd M_;                      // G1^-T G2^T (r x (k - r))
  Eigen::MatrixXd gram_;                   // N^T N
  Eigen::LLT<Eigen::MatrixXd> null_gram_;  // of N^T N = I + M^T M
  mutable Eigen::MatrixXd permuted_, t_;
  mutable Eigen::VectorXd t_column_;
};

template <typename Rhs>
void PsdPseudoInverse::permute_in(const Eigen::MatrixBase<Rhs>& c) const {
  const auto k = static_cast<Eigen::Index>(order_.size());
  permuted_.resize(k, c.cols());
  for (Eigen::Index i = 0; i < k; ++i) permuted_.row(i) = c.row(order_[static_cast<std::size_t>(i)]);
}

template <typename Y, typename T>
void PsdPseudoInverse::project_off_null_space(Y&& y, T& t) const {
  const Eigen::Index r = rank_, q = static_cast<Eigen::Index>(order_.size()) - r;
  if (q == 0) return;
  t.noalias() = y.bottomRows(q) - M_.transpose() * y.topRows(r);  // N^T y
  null_gram_.solveInPlace(t);
  y.topRows(r).noalias() += M_ * t;  // y -= N t
  y.bottomRows(q) -= t;
}

template <typename Y>
void PsdPseudoInverse::solve_permuted(Y&& y) const {
  const Eigen::Index r = rank_;
  const auto G1 = G_.topLeftCorner(r, r).template triangularView<Eigen::Lower>();
  G1.solveInPlace(y.topRows(r));
  G1.transpose().solveInPlace(y.topRows(r));
  y.bottomRows(y.rows() - r).setZero();
}

template <typename Rhs, typename Out>
void PsdPseudoInverse::solve(const Eigen::MatrixBase<Rhs>& c, Eigen::PlainObjectBase<Out>& x) const {
  const auto k = static_cast<Eigen::Index>(order_.size());
  permute_in(c);  // (c is read here only: x may be c)
  if (c.cols() == 1) {
    project_off_null_space(permuted_.col(0), t_column_);
    solve_permuted(permuted_.col(0));
    project_off_null_space(permuted_.col(0), t_column_);
  } else {
    project_off_null_space(permuted_, t_);
    solve_permuted(permuted_);
    project_off_null_space(permuted_, t_);
  }
  x.resize(k, c.cols());
  for (Eigen::Index i = 0; i < k; ++i) x.row(order_[static_cast<std::size_t>(i)]) = permuted_.row(i);
}

template <typename Rhs>
void PsdPseudoInverse::half_solve(const Eigen::MatrixBase<Rhs>& C, Eigen::MatrixXd& Z) const {
  permute_in(C);
  project_off_null_space(permuted_, t_);
  Z = permuted_.topRows(rank_);
  G_.topLeftCorner(rank_, rank_).triangularView<Eigen::Lower>().solveInPlace(Z);
}

}  // namespace wysiwyf::haptics
