#pragma once
// Closed-form inverse kinematics of a UR-type 6R arm (Universal Robots: joints 2, 3, 4 parallel,
// DH twists 90 0 0 90 -90 0 deg, a4 = a5 = 0), after Hawkins, "Analytic Inverse Kinematics for
// the Universal Robots UR-5/UR-10 Arms" (2013), in the DH terms of dh_geometry.hpp and for any
// d1..d5, a1, a2, a3 (detail in ur_ik.cpp).
#include <array>

#include "arm_model/dh_geometry.hpp"

namespace wysiwyf::robot::detail {

// One of the eight branches. Index bits: 1 = second shoulder root (theta1), 2 = wrist
// theta5 < 0, 4 = second elbow root (theta3).
struct UrBranch {
  std::array<double, 6> theta{};  // DH angles (joint value = theta - offset)
  bool valid = false;             // the branch reaches the pose
  bool singular = false;          // sin(theta5) ~ 0: theta6 was kept at theta6_ref
};

// All eight branches for dh0_T_dh6 (the pose of DH frame 6 in DH frame 0); theta6_ref is used
// at the wrist singularity, where only theta4 + theta6 (or their difference) is determined.
void ur_ik(const DhChain& dh, const Eigen::Isometry3d& dh0_T_dh6, double theta6_ref, std::array<UrBranch, 8>& out);

}  // namespace wysiwyf::robot::detail
