#include "rigid_body/psd_pseudo_inverse.hpp"

#include <cmath>
#include <numeric>
#include <utility>

namespace wysiwyf::haptics {
namespace {

// The dot product of n entries from a and b (Eigen's, vectorised: a plain loop may not be
// reordered).
double dot(const double* a, const double* b, Eigen::Index n) {
  return Eigen::Map<const Eigen::VectorXd>(a, n).dot(Eigen::Map<const Eigen::VectorXd>(b, n));
}

// U^T z = y, then U x = z, in place on y's first n entries: U (leading dimension ld) upper
// triangular, read by columns (U's column i is the contiguous U(0..i, i)).
void forward_upper_transposed(const double* U, Eigen::Index ld, Eigen::Index n, double* y) {
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* u = U + i * ld;
    y[i] = (y[i] - dot(u, y, i)) / u[i];
  }
}

void backward_upper(const double* U, Eigen::Index ld, Eigen::Index n, double* y) {
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    const double* u = U + i * ld;
    const double x = y[i] /= u[i];
    for (Eigen::Index l = 0; l < i; ++l) y[l] -= u[l] * x;
  }
}

// The Cholesky factor U (U^T U = S) of the symmetric S whose upper triangle U holds (columns
// contiguous), in place; false where a pivot is not positive (round-off).
bool cholesky_upper(Eigen::MatrixXd& U) {
  for (Eigen::Index j = 0; j < U.cols(); ++j) {
    double* uj = U.col(j).data();
    const double pivot = uj[j] - dot(uj, uj, j);
    if (!(pivot > 0)) return false;
    uj[j] = std::sqrt(pivot);
    for (Eigen::Index i = j + 1; i < U.cols(); ++i) {
      double* ui = U.col(i).data();
      ui[j] = (ui[j] - dot(uj, ui, j)) / uj[j];
    }
  }
  return true;
}

}  // namespace

void PsdPseudoInverse::compute(const Eigen::MatrixXd& B, double threshold) {
  const Eigen::Index k = B.rows();
  diagonal_ = B.diagonal();
  order_.resize(static_cast<std::size_t>(k));
  std::iota(order_.begin(), order_.end(), Eigen::Index{0});
  H_.resize(k, k);
  rank_ = 0;
  const double cutoff = threshold * (k > 0 ? diagonal_.maxCoeff() : 0.0);
  // Row j of G (column j of H): the largest remaining pivot first, so what is left when it falls
  // below the cutoff is B less its rank-j part, all round-off.
  for (Eigen::Index j = 0; j < k; ++j) {
    Eigen::Index p = 0;
    const double pivot = diagonal_.tail(k - j).maxCoeff(&p);
    p += j;
    if (!(pivot > cutoff)) break;
    if (p != j) {
      std::swap(diagonal_[j], diagonal_[p]);
      std::swap(order_[static_cast<std::size_t>(j)], order_[static_cast<std::size_t>(p)]);
      H_.col(j).head(j).swap(H_.col(p).head(j));
    }
    const double g = std::sqrt(pivot);
    double* hj = H_.col(j).data();
    hj[j] = g;
    const Eigen::Index bj = order_[static_cast<std::size_t>(j)];
    for (Eigen::Index i = j + 1; i < k; ++i) {
      double* hi = H_.col(i).data();
      hi[j] = (B(order_[static_cast<std::size_t>(i)], bj) - dot(hi, hj, j)) / g;
      diagonal_[i] -= hi[j] * hi[j];
    }
    rank_ = j + 1;
  }
  const Eigen::Index r = rank_, q = k - r;
  in_range_ = q >= r;
  if (in_range_) {
    // G^T G = sum over G's rows g_i g_i^T (H_'s columns' first r entries, G1^T's zeros filled in),
    // then its Cholesky factor U (upper, U^T U = G^T G), in place.
    for (Eigen::Index i = 0; i < r; ++i) H_.col(i).segment(i + 1, r - i - 1).setZero();
    gram_.setZero(r, r);
    for (Eigen::Index i = 0; i < k; ++i) {
      const double* h = H_.col(i).data();
      for (Eigen::Index c = 0; c < r; ++c) {
        double* u = gram_.col(c).data();
        for (Eigen::Index l = 0; l <= c; ++l) u[l] += h[l] * h[c];
      }
    }
    // (G has full column rank; round-off could still defeat the factor)
    if (cholesky_upper(gram_)) return;
    in_range_ = false;  // the projections, whose factor (of I + M^T M) cannot fail
  }
  // M = G1^-T G2^T = H1^-1 H2, column by column.
  M_.resize(r, q);
  for (Eigen::Index c = 0; c < q; ++c) {
    M_.col(c) = H_.col(r + c).head(r);
    backward_upper(H_.data(), k, r, M_.col(c).data());
  }
  if (q == 0) return;
  // N^T N = I + M^T M, and its Cholesky factor U (upper, U^T U = N^T N), in place.
  gram_.resize(q, q);
  for (Eigen::Index i = 0; i < q; ++i)
    for (Eigen::Index j = 0; j <= i; ++j)
      gram_(j, i) = (i == j ? 1.0 : 0.0) + dot(M_.col(j).data(), M_.col(i).data(), r);
  cholesky_upper(gram_);  // (every pivot >= 1: I + M^T M)
}

void PsdPseudoInverse::project_off_null_space(double* y) const {
  const Eigen::Index r = rank_, q = static_cast<Eigen::Index>(order_.size()) - r;
  if (q == 0) return;
  t_.resize(q);
  double* t = t_.data();
  for (Eigen::Index c = 0; c < q; ++c) t[c] = y[r + c] - dot(M_.col(c).data(), y, r);  // N^T y
  forward_upper_transposed(gram_.data(), q, q, t);
  backward_upper(gram_.data(), q, q, t);
  for (Eigen::Index c = 0; c < q; ++c) {  // y -= N t
    const double* m = M_.col(c).data();
    for (Eigen::Index l = 0; l < r; ++l) y[l] += m[l] * t[c];
    y[r + c] -= t[c];
  }
}

void PsdPseudoInverse::project_off_null_space_all() const {
  const Eigen::Index r = rank_, q = static_cast<Eigen::Index>(order_.size()) - r;
  if (q == 0) return;
  Eigen::MatrixXd& y = permuted_;
  t_matrix_.noalias() = y.bottomRows(q);
  t_matrix_.noalias() -= M_.transpose() * y.topRows(r);  // N^T y
  const auto U = gram_.triangularView<Eigen::Upper>();
  U.transpose().solveInPlace(t_matrix_);
  U.solveInPlace(t_matrix_);
  y.topRows(r).noalias() += M_ * t_matrix_;  // y -= N t
  y.bottomRows(q) -= t_matrix_;
}

void PsdPseudoInverse::range_half(const double* y, double* z) const {
  const Eigen::Index r = rank_, k = static_cast<Eigen::Index>(order_.size());
  for (Eigen::Index l = 0; l < r; ++l) z[l] = 0;
  for (Eigen::Index i = 0; i < k; ++i) {  // G^T y
    const double* h = H_.col(i).data();
    for (Eigen::Index l = 0; l < r; ++l) z[l] += h[l] * y[i];
  }
  forward_upper_transposed(gram_.data(), r, r, z);
  backward_upper(gram_.data(), r, r, z);
}

void PsdPseudoInverse::range_solve(double* y) const {
  const Eigen::Index r = rank_, k = static_cast<Eigen::Index>(order_.size());
  t_.resize(r);
  double* z = t_.data();
  range_half(y, z);
  forward_upper_transposed(gram_.data(), r, r, z);
  backward_upper(gram_.data(), r, r, z);
  for (Eigen::Index i = 0; i < k; ++i) y[i] = dot(H_.col(i).data(), z, r);  // G z
}

void PsdPseudoInverse::range_half_all(Eigen::MatrixXd& Z) const {
  const Eigen::Index r = rank_, k = static_cast<Eigen::Index>(order_.size()), n = permuted_.cols();
  if (n < kManyColumns) {
    Z.resize(r, n);
    for (Eigen::Index j = 0; j < n; ++j) range_half(permuted_.col(j).data(), Z.col(j).data());
    return;
  }
  Z.noalias() = H_.topLeftCorner(r, k) * permuted_;
  const auto U = gram_.topLeftCorner(r, r).triangularView<Eigen::Upper>();
  U.transpose().solveInPlace(Z);
  U.solveInPlace(Z);
}

void PsdPseudoInverse::forward_all() const {
  H_.topLeftCorner(rank_, rank_).triangularView<Eigen::Upper>().transpose().solveInPlace(permuted_.topRows(rank_));
}

void PsdPseudoInverse::forward(double* y) const { forward_upper_transposed(H_.data(), H_.rows(), rank_, y); }

void PsdPseudoInverse::solve_permuted(double* y) const {
  forward_upper_transposed(H_.data(), H_.rows(), rank_, y);
  backward_upper(H_.data(), H_.rows(), rank_, y);
  for (Eigen::Index i = rank_; i < static_cast<Eigen::Index>(order_.size()); ++i) y[i] = 0;
}

}  // namespace wysiwyf::haptics
