#pragma once
// The static poses of the wrist calibration and the gravity the sensor feels in each. The poses
// keep the arm where it is (q_home) and turn its last three joints, so the sensor's orientation
// covers the sphere while the arm moves little: gravity directions chosen farthest apart (greedy,
// from a grid within the joint limits), which keeps the fit's condition number near its best.
#include <vector>

#include <Eigen/Core>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot {

// Gravity (gravity_base, base frame) in frame f's axes with the arm at q.
Eigen::Vector3d gravity_in_frame(const ArmModel& arm, const JointRef& q, FrameId f,
                                 const Eigen::Vector3d& gravity_base = standard_gravity());

// `count` joint vectors within the limits, q_home's first joints and its last three turned, whose
// sensor (frame f) gravity directions lie far apart. Throws std::invalid_argument when q_home has
// the wrong size or lies outside the limits, or count is below 1.
std::vector<JointVector> wrist_calibration_poses(const ArmModel& arm, const JointRef& q_home, FrameId f, int count,
                                                 const Eigen::Vector3d& gravity_base = standard_gravity());

}  // namespace wysiwyf::robot
