#pragma once
// The uncertainty of a pose eye_T_x as a 6x6 covariance over (dt, dtheta) in eye coordinates
// (the perturbed pose: rotation exp(dtheta) R, translation t + dt), and how it carries over to
// a pose composed with a known transform.
#include <Eigen/Geometry>

namespace wysiwyf::vision::frames {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d S;
  S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return S;
}

// The covariance of eye_T_y = eye_T_x * x_T_y given that of eye_T_x, x_T_y known exactly:
// eye_t_y = exp(dtheta) R x_t_y + t + dt errs by dt - [R x_t_y]x dtheta; the rotation error is
// the same.
inline Eigen::Matrix<double, 6, 6> compose_covariance(const Eigen::Matrix<double, 6, 6>& eye_T_x_cov,
                                                      const Eigen::Isometry3d& eye_T_x,
                                                      const Eigen::Isometry3d& x_T_y) {
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Identity();
  J.block<3, 3>(0, 3) = -skew(eye_T_x.linear() * x_T_y.translation());
  return J * eye_T_x_cov * J.transpose();
}

}  // namespace wysiwyf::vision::frames
