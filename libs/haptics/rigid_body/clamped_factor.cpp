#include "rigid_body/clamped_factor.hpp"

#include <cmath>

namespace wysiwyf::haptics {

void ClampedFactor::forward(LcpVector& v) const {
  if (n_ > 0) L_.topLeftCorner(n_, n_).triangularView<Eigen::Lower>().solveInPlace(v);
}

void ClampedFactor::back(LcpVector& y) const {
  if (n_ > 0) L_.topLeftCorner(n_, n_).transpose().triangularView<Eigen::Upper>().solveInPlace(y);
}

bool ClampedFactor::append(const LcpVector& l, double a_ii, double floor) {
  const double pivot = a_ii - (n_ > 0 ? l.head(n_).squaredNorm() : 0.0);
  if (!(pivot > floor)) return false;
  L_.row(n_).head(n_) = l.head(n_).transpose();
  L_.col(n_).head(n_).setZero();
  L_(n_, n_) = std::sqrt(pivot);
  ++n_;
  return true;
}

void ClampedFactor::remove(int k) {
  // Without row k, L's rows below it reach one column past the diagonal. L L^T does not change
  // when L's columns are rotated, so Givens rotations of columns (j, j + 1) take each such entry
  // away in turn, and the last column empties.
  for (int r = k; r + 1 < n_; ++r) L_.row(r).head(n_) = L_.row(r + 1).head(n_);
  const int m = n_ - 1;  // rows 0..m-1 remain
  for (int j = k; j < m; ++j) {
    const double a = L_(j, j), b = L_(j, j + 1);
    const double r = std::hypot(a, b);
    if (r == 0.0) continue;
    const double c = a / r, s = b / r;
    for (int row = j; row < m; ++row) {
      const double x = L_(row, j), y = L_(row, j + 1);
      L_(row, j) = c * x + s * y;
      L_(row, j + 1) = c * y - s * x;
    }
    L_(j, j + 1) = 0;
  }
  L_.col(m).head(n_).setZero();
  L_.row(m).head(n_).setZero();
  n_ = m;
}

}  // namespace wysiwyf::haptics
