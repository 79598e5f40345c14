#pragma once
// Where the plate goes to display a feature, and whether the arm gets there: the feature's plate
// frame (z out of the face, the plate's knob on the virtual knob) turned about the face's normal
// by 0, 90, 180 or 270 degrees (the plate is square: each shows the face), and for each of them
// whether the arm reaches it along the planned path on the inverse kinematics branch it is on,
// within its joint limits.
#include <string>
#include <vector>

#include "arm_model/arm_model.hpp"
#include "plate_path.hpp"
#include "scene/scene.hpp"

namespace wysiwyf::display {

// The four plate poses that display `feature` (its body at base_T_obj), nearest in orientation
// to base_T_now first.
std::vector<Eigen::Isometry3d> plate_poses(const haptics::DisplayFeature& feature, const Eigen::Isometry3d& base_T_obj,
                                           const Eigen::Isometry3d& base_T_now);

// Whether the arm, at q_now, can follow `path` (poses of the model's tip frame) to its end: inverse
// kinematics every `step` seconds of the path at full speed, each solution within limits and
// within max_joint_step of the last (no branch change). Empty when it can; else why not. q_end:
// the joints at the end.
std::string path_reachable(const robot::ArmModel& model, PlatePath path, const robot::JointRef& q_now,
                           robot::JointVector& q_end, double step = 0.01, double max_joint_step = 0.35);

}  // namespace wysiwyf::display
