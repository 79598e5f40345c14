#pragma once
// Small rigid-motion helpers for the hot paths (internal to the library).
#include <cmath>

#include <Eigen/Core>

namespace wysiwyf::robot::detail {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

// R <- R * Rz(theta), given c = cos(theta), s = sin(theta): only two columns change.
inline void post_rotate_z(Eigen::Matrix3d& R, double c, double s) {
  const Eigen::Vector3d x = R.col(0);
  const Eigen::Vector3d y = R.col(1);
  R.col(0) = c * x + s * y;
  R.col(1) = c * y - s * x;
}

// Angle in (-pi, pi].
inline double wrap_to_pi(double a) {
  a = std::remainder(a, kTwoPi);  // [-pi, pi]
  return a <= -kPi ? a + kTwoPi : a;
}

}  // namespace wysiwyf::robot::detail
