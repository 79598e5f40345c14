#pragma once
// ArmModel's workspace on KDL (internal to the library): the chain, one segment per moving
// joint, its solvers and their buffers, sized once. KDL's solvers keep a reference to the chain
// and its joints cache their last pose, so a KdlParts never moves and serves one thread.
#include <Eigen/Cholesky>
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntspaceinertiamatrix.hpp>

#include "arm_model/arm_types.hpp"

namespace wysiwyf::robot::detail {

struct KdlParts {
  // Segment j: joint j in body j's frame, tip = body j+1's frame at q = 0, body j+1's inertia.
  KDL::Chain chain;
  // Three massless slides along base x, y, z, then `chain`: RNEA with gravity g is RNEA without
  // gravity whose base accelerates by -g, which lets one KDL solver take any gravity per call.
  KDL::Chain dynamic_chain;
  KDL::ChainFkSolverPos_recursive fk;
  KDL::ChainJntToJacSolver jac;
  KDL::ChainIdSolver_RNE rne;
  KDL::ChainDynParam dyn;
  KDL::JntArray q;                    // n
  KDL::JntArray dq, dqd, dqdd, dtau;  // n + 3, for dynamic_chain
  KDL::Jacobian J;                    // 6 x n
  KDL::JntSpaceInertiaMatrix H;       // n x n
  KDL::Wrenches no_wrench;            // n + 3 zero external wrenches
  KDL::Frame frame;
  Eigen::LDLT<JointMatrix> ldlt;

  // Builds the solvers and buffers for `kinematic_chain`.
  explicit KdlParts(const KDL::Chain& kinematic_chain);
  // A copy builds its own solvers on its own copy of the chain.
  KdlParts(const KdlParts& other) : KdlParts(other.chain) {}
  KdlParts& operator=(const KdlParts&) = delete;
};

// KDL frame to Eigen isometry.
inline Eigen::Isometry3d to_eigen(const KDL::Frame& f) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = f.M(r, c);
    T.translation()[r] = f.p(r);
  }
  return T;
}

// Eigen isometry to KDL frame.
inline KDL::Frame to_kdl(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d& R = T.linear();
  const Eigen::Vector3d& p = T.translation();
  return KDL::Frame(KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)),
                    KDL::Vector(p.x(), p.y(), p.z()));
}

// Eigen vector to KDL vector.
inline KDL::Vector to_kdl(const Eigen::Vector3d& v) { return KDL::Vector(v.x(), v.y(), v.z()); }

}  // namespace wysiwyf::robot::detail
