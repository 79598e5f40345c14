// Forward kinematics, the geometric Jacobian and the damped least squares step, on KDL's
// recursive solvers: a frame's pose is its body's pose (KDL, up to that body's segment) times
// the frame's fixed offset in the body.
#include <Eigen/Cholesky>

#include "arm_model/arm_model.hpp"
#include "arm_model/kdl_parts.hpp"
#include "puma_model/rigid.hpp"

namespace wysiwyf::robot {

Eigen::Isometry3d ArmModel::body_pose(const JointRef& q, int body) const {
  detail::KdlParts& k = *kdl_;
  k.q.data = q;
  k.fk.JntToCart(k.q, k.frame, body);
  return detail::to_eigen(k.frame);
}

Eigen::Isometry3d ArmModel::fk(const JointRef& q, FrameId f) const {
  const Frame& fr = frames_[check(f)];
  check_size(q, "q");
  return body_pose(q, fr.body) * fr.body_T_frame;
}

ArmJacobian ArmModel::jacobian(const JointRef& q, FrameId f) const {
  const Frame& fr = frames_[check(f)];
  check_size(q, "q");
  detail::KdlParts& k = *kdl_;
  k.q.data = q;
  // KDL: the Jacobian of the body's origin in base coordinates; move its reference point to the
  // frame's origin (base_R_body * body_p_frame away).
  k.jac.JntToJac(k.q, k.J, fr.body);
  k.fk.JntToCart(k.q, k.frame, fr.body);
  const Eigen::Vector3d& p = fr.body_T_frame.translation();
  k.J.changeRefPoint(k.frame.M * KDL::Vector(p.x(), p.y(), p.z()));
  return k.J.data;
}

JointVector ArmModel::dls_step(const JointRef& q, const Eigen::Isometry3d& base_T_target, double lambda,
                               FrameId f) const {
  const Vector6d error = detail::pose_error(base_T_target, fk(q, f));
  const ArmJacobian J = jacobian(q, f);
  const Matrix6d A = J * J.transpose() + lambda * lambda * Matrix6d::Identity();
  return J.transpose() * A.ldlt().solve(error);
}

}  // namespace wysiwyf::robot
