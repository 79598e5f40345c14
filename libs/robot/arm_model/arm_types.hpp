#pragma once
// Joint-space types of the generic arm model (ArmModel): vectors and matrices of up to
// kMaxArmDof joints whose size is set at run time but whose storage is inline (no heap), the
// joint kinds and the URDF's joint limits. Frame ids, body inertias and the standard gravity are
// the PUMA model's (puma_model/types.hpp), so both models speak the same small types.
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "puma_model/types.hpp"

namespace wysiwyf::robot {

// The most moving joints an ArmModel holds (a 7-joint arm on a rail or lift still fits).
constexpr int kMaxArmDof = 8;

// n joint values (n = ArmModel::dof()), stored inline.
using JointVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxArmDof, 1>;
// n x n joint-space matrix (mass matrix), stored inline.
using JointMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxArmDof, kMaxArmDof>;
// 6 x n geometric Jacobian [v; w], stored inline.
using ArmJacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, kMaxArmDof>;
// A read-only view of n joint values: binds a JointVector, an Eigen::VectorXd or a Vector6d
// without a copy (an expression such as q + dq is first evaluated into a heap VectorXd).
using JointRef = Eigen::Ref<const Eigen::VectorXd>;

enum class JointKind {
  kRevolute,    // rotation about the URDF axis, with position limits
  kContinuous,  // rotation without position limits (lower = -inf, upper = +inf)
  kPrismatic,   // translation along the URDF axis, with position limits
};

// Per joint, from the URDF <limit>: position [rad or m], velocity [rad/s or m/s], effort [N m or N].
struct ArmLimits {
  JointVector lower;
  JointVector upper;
  JointVector velocity;
  JointVector effort;

  // Whether every joint of q lies within its position limits (widened by tolerance).
  bool within(const JointRef& q, double tolerance = 0.0) const {
    return ((q.array() >= lower.array() - tolerance) && (q.array() <= upper.array() + tolerance)).all();
  }
};

}  // namespace wysiwyf::robot
