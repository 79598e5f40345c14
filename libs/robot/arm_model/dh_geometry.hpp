#pragma once
// A revolute chain's standard Denavit-Hartenberg description, derived from where its joint axes
// lie at q = 0 (any URDF layout), so that closed-form IK written in DH terms applies to any URDF
// of that geometry:
//
//   base_T_body_n(q) = base_T_dh0 * A_1(q_1 + offset_1) ... A_n(q_n + offset_n) * dhn_T_body,
//   A_i(theta) = Rz(theta) Tz(d_i) Tx(a_i) Rx(alpha_i).
//
// z_{i-1} is joint i's axis (the URDF's direction); x_i is the common normal of axes i and i+1
// (through the previous origin when they are parallel), signed to agree with x_{i-1}; frame n
// is frame n-1 turned by joint n (d_n = a_n = alpha_n = 0), dhn_T_body the rest.
#include <array>
#include <string>

#include "arm_model/arm_types.hpp"

namespace wysiwyf::robot::detail {

struct DhChain {
  int n = 0;
  std::array<double, kMaxArmDof> d{}, a{}, alpha{}, offset{};
  Eigen::Isometry3d base_T_dh0 = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d dhn_T_body = Eigen::Isometry3d::Identity();
};

// One joint axis at q = 0, in base coordinates.
struct AxisLine {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit
};

// A_i(theta) = Rz(theta) Tz(d) Tx(a) Rx(alpha).
Eigen::Isometry3d dh_transform(double theta, double d, double a, double alpha);

// The DH description of n revolute joints from their axes at q = 0 and the last body's pose at q = 0.
DhChain dh_from_axes(const AxisLine* axes, int n, const Eigen::Isometry3d& base_T_body_at_zero);

// base_T_body_n for joint values q by the DH product.
Eigen::Isometry3d dh_forward(const DhChain& dh, const JointRef& q);

// Whether the chain is UR-type (6 joints, twists 90 0 0 90 -90 deg, a4 = a5 = 0, a2 and a3 not
// zero): empty when it is, else what differs.
std::string ur_geometry_mismatch(const DhChain& dh);

}  // namespace wysiwyf::robot::detail
