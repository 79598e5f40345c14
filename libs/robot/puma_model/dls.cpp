// Damped least squares step (Wampler / Nakamura): usable through and near singularities.
#include <Eigen/Cholesky>

#include "puma_model/puma_model.hpp"
#include "puma_model/rigid.hpp"

namespace wysiwyf::robot {

Vector6d PumaModel::dls_step(const Vector6d& q, const Eigen::Isometry3d& base_T_target, double lambda,
                             FrameId f) const {
  const Vector6d error = detail::pose_error(base_T_target, fk(q, f));
  const Matrix6d J = jacobian(q, f);
  const Matrix6d A = J * J.transpose() + lambda * lambda * Matrix6d::Identity();
  return J.transpose() * A.ldlt().solve(error);
}

}  // namespace wysiwyf::robot
