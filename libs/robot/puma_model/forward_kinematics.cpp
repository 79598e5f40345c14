// Forward kinematics and the geometric Jacobian: the URDF's joint origins composed with
// rotations about local z.
#include "puma_model/puma_model.hpp"
#include "puma_model/rigid.hpp"

namespace wysiwyf::robot {

Eigen::Isometry3d PumaModel::fk(const Vector6d& q, FrameId f) const {
  const Frame& fr = frames_[check(f)];
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int j = 0; j < fr.body; ++j) {
    const JointOrigin& o = joints_[static_cast<std::size_t>(j)];
    p += R * o.p;
    R = R * o.R;
    detail::post_rotate_z(R, std::cos(q[j]), std::sin(q[j]));
  }
  Eigen::Isometry3d base_T_frame;
  base_T_frame.linear() = R * fr.R;
  base_T_frame.translation() = p + R * fr.p;
  base_T_frame.makeAffine();
  return base_T_frame;
}

Matrix6d PumaModel::jacobian(const Vector6d& q, FrameId f) const {
  const Frame& fr = frames_[check(f)];
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, kDof> origin, axis;
  for (int j = 0; j < fr.body; ++j) {
    const JointOrigin& o = joints_[static_cast<std::size_t>(j)];
    p += R * o.p;
    R = R * o.R;
    origin.col(j) = p;
    axis.col(j) = R.col(2);  // rotating about z keeps z
    detail::post_rotate_z(R, std::cos(q[j]), std::sin(q[j]));
  }
  const Eigen::Vector3d tip = p + R * fr.p;
  Matrix6d J = Matrix6d::Zero();
  for (int j = 0; j < fr.body; ++j) {
    J.block<3, 1>(0, j) = axis.col(j).cross(tip - origin.col(j));
    J.block<3, 1>(3, j) = axis.col(j);
  }
  return J;
}

}  // namespace wysiwyf::robot
