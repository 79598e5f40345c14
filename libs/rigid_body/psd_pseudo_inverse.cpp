#include "rigid_body/psd_pseudo_inverse.hpp"

#include <cmath>
#include <numeric>
#include <utility>

namespace wysiwyf::haptics {

void PsdPseudoInverse::compute(const Eigen::MatrixXd& B, double threshold) {
  const Eigen::Index k = B.rows();
  work_ = B;
  diagonal_ = B.diagonal();
  order_.resize(static_cast<std::size_t>(k));
  std::iota(order_.begin(), order_.end(), Eigen::Index{0});
  G_.resize(k, k);
  rank_ = 0;
  const double cutoff = threshold * (k > 0 ? diagonal_.maxCoeff() : 0.0);
  // Column j of G: the largest remaining pivot first, so what is left when it falls below the
  // cutoff is B less its rank-j part, all round-off.
  for (Eigen::Index j = 0; j < k; ++j) {
    Eigen::Index p = 0;
    const double pivot = diagonal_.tail(k - j).maxCoeff(&p);
    p += j;
    if (!(pivot > cutoff)) break;
    if (p != j) {
      work_.row(j).swap(work_.row(p));
      work_.col(j).swap(work_.col(p));
      std::swap(diagonal_[j], diagonal_[p]);
      std::swap(order_[static_cast<std::size_t>(j)], order_[static_cast<std::size_t>(p)]);
      G_.row(j).head(j).swap(G_.row(p).head(j));
    }
    const double g = std::sqrt(pivot);
    G_(j, j) = g;
    const Eigen::Index below = k - j - 1;
    G_.col(j).tail(below) =
        (work_.col(j).tail(below) - G_.bottomLeftCorner(below, j) * G_.row(j).head(j).transpose()) / g;
    diagonal_.tail(below) -= G_.col(j).tail(below).cwiseAbs2();
    rank_ = j + 1;
  }
  const Eigen::Index r = rank_, q = k - r;
  for (Eigen::Index j = 0; j < r; ++j) G_.col(j).head(j).setZero();  // (lower triangular)
  M_ = G_.bottomLeftCorner(q, r).transpose();
  G_.topLeftCorner(r, r).triangularView<Eigen::Lower>().transpose().solveInPlace(M_);
  if (q == 0) return;
  gram_.setIdentity(q, q);
  gram_.noalias() += M_.transpose() * M_;
  null_gram_.compute(gram_);
}

}  // namespace wysiwyf::haptics
