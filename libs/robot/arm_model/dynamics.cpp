// Rigid-body dynamics on KDL: recursive Newton-Euler (ChainIdSolver_RNE) on the chain behind
// three massless base slides, whose acceleration -g stands for gravity g, and the mass matrix by
// the composite rigid body algorithm (ChainDynParam::JntToMass); rotor inertia on the diagonal.
#include "arm_model/arm_model.hpp"
#include "arm_model/kdl_parts.hpp"

namespace wysiwyf::robot {

JointVector ArmModel::rnea(const JointRef& q, const JointRef& qd, const JointRef& qdd,
                           const Eigen::Vector3d& gravity) const {
  check_size(q, "q");
  check_size(qd, "qd");
  check_size(qdd, "qdd");
  detail::KdlParts& k = *kdl_;
  const int n = dof();
  k.dq.data.head<3>().setZero();
  k.dq.data.tail(n) = q;
  k.dqd.data.head<3>().setZero();
  k.dqd.data.tail(n) = qd;
  k.dqdd.data.head<3>() = -gravity;
  k.dqdd.data.tail(n) = qdd;
  k.rne.CartToJnt(k.dq, k.dqd, k.dqdd, k.no_wrench, k.dtau);
  return k.dtau.data.tail(n) + rotor_inertia_.cwiseProduct(JointVector(qdd));
}

JointMatrix ArmModel::mass_matrix(const JointRef& q) const {
  check_size(q, "q");
  detail::KdlParts& k = *kdl_;
  k.q.data = q;
  k.dyn.JntToMass(k.q, k.H);
  JointMatrix M = k.H.data;
  M.diagonal() += rotor_inertia_;
  return M;
}

JointVector ArmModel::gravity_torques(const JointRef& q, const Eigen::Vector3d& gravity) const {
  const JointVector zero = JointVector::Zero(dof());
  return rnea(q, zero, zero, gravity);
}

JointVector ArmModel::coriolis(const JointRef& q, const JointRef& qd) const {
  const JointVector zero = JointVector::Zero(dof());  // a named vector: a Ref to an expression would allocate
  return rnea(q, qd, zero, Eigen::Vector3d::Zero());
}

JointVector ArmModel::forward_dynamics(const JointRef& q, const JointRef& qd, const JointRef& tau,
                                       const Eigen::Vector3d& gravity) const {
  check_size(tau, "tau");
  const JointVector zero = JointVector::Zero(dof());
  const JointVector bias = rnea(q, qd, zero, gravity);
  const JointMatrix M = mass_matrix(q);
  detail::KdlParts& k = *kdl_;
  k.ldlt.compute(M);
  return k.ldlt.solve(JointVector(tau - bias));
}

}  // namespace wysiwyf::robot
