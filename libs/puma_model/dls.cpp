// Damped least squares step (Wampler / Nakamura): usable through and near singularities.
#include <Eigen/Cholesky>

#include "puma_model/puma_model.hpp"

namespace wysiwyf::robot {

Vector6d PumaModel::dls_step(const Vector6d& q, const Eigen::Isometry3d& base_T_target, double lambda,
                             FrameId f) const {
  const Eigen::Isometry3d base_T_frame = fk(q, f);
  Vector6d error;
  error.head<3>() = base_T_target.translation() - base_T_frame.translation();
  const Eigen::AngleAxisd rotation(Eigen::Matrix3d(base_T_target.linear() * base_T_frame.linear().transpose()));
  error.tail<3>() = rotation.angle() * rotation.axis();
  const Matrix6d J = jacobian(q, f);
  const Matrix6d A = J * J.transpose() + lambda * lambda * Matrix6d::Identity();
  return J.transpose() * A.ldlt().solve(error);
}

}  // namespace wysiwyf::robot
