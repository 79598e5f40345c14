#pragma once
// Small rigid-motion helpers for the hot paths (internal to the library).
#include <cmath>

#include <Eigen/Geometry>

#include "puma_model/types.hpp"

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

// [position error; rotation vector of R_target R^T], in base coordinates: what a damped least
// squares or Levenberg-Marquardt step drives to zero.
inline Vector6d pose_error(const Eigen::Isometry3d& target, const Eigen::Isometry3d& current) {
  Vector6d e;
  e.head<3>() = target.translation() - current.translation();
  const Eigen::AngleAxisd rotation(Eigen::Matrix3d(target.linear() * current.linear().transpose()));
  e.tail<3>() = rotation.angle() * rotation.axis();
  return e;
}

}  // namespace wysiwyf::robot::detail
