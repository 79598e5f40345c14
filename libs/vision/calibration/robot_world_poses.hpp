#pragma once
// The poses the arm takes for the robot-world calibration: the board on the plate brought in front
// of the fixed camera, 0.75 to 1.05 m from it along rays spread over the middle of the image,
// tilted 15 to 35 degrees about varied axes (rotation about different axes is what separates the
// camera's pose from the board's mount), each reached by the arm's IK nearest to the pose before it
// and kept only when every board corner lands inside the image.
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "arm_model/arm_model.hpp"
#include "calibration/camera_model.hpp"
#include "calibration/charuco_target.hpp"

namespace wysiwyf::vision::calibration {

// Where the board lies on the plate (frame `dev`: the plate's front face, z out of it): centred,
// flat on the face, read the right way up by a camera facing the plate.
Eigen::Isometry3d dev_T_board(const CharucoTarget& target);

// `count` joint vectors within the limits (fewer when the camera sees too little of the arm's
// reach; seeded). flange: the frame the board is fixed to (flange_T_board from it).
std::vector<robot::JointVector> robot_world_poses(const robot::ArmModel& arm, const Eigen::VectorXd& q_home,
                                                  robot::FrameId flange, const Eigen::Isometry3d& flange_T_board,
                                                  const Eigen::Isometry3d& base_T_eye, const CameraIntrinsics& camera,
                                                  const CharucoTarget& target, int count, std::mt19937& rng);

}  // namespace wysiwyf::vision::calibration
