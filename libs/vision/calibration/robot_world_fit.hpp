#pragma once
// Where a fixed camera stands in the robot's base frame (robot-world / hand-eye calibration): the
// arm holds a ChArUco board on its flange through a set of poses; at each, forward kinematics
// gives base_T_flange and the camera sees the board's corners. Both unknowns, base_T_eye and
// flange_T_board, close the loop eye_T_base * base_T_flange_i * flange_T_board = eye_T_board_i.
// cv::calibrateRobotWorldHandEye (Shah's closed form) on the boards' PnP poses starts it; a
// Levenberg-Marquardt fit of both transforms to every corner of every view (reprojection error
// in pixels, the camera's intrinsics held) finishes it. A pose set with too few poses or too
// little rotation is refused; so is one that leaves a pose's error over the limit, and when two
// halves of the set each fit but not together, the reason says that the camera (or the board)
// moved between them.
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "calibration/camera_model.hpp"
#include "calibration/charuco_target.hpp"

namespace wysiwyf::vision::calibration {

// One pose of the arm and what the camera saw of the board there.
struct FlangeView {
  std::string label;  // how reports name it ("pose 3", an image file)
  Eigen::Isometry3d base_T_flange = Eigen::Isometry3d::Identity();
  std::vector<cv::Point2f> corners;  // px, as detected (distorted image)
  std::vector<int> ids;              // charuco ids
};

struct RobotWorldLimits {
  int min_poses = 8;                // usable poses, fewer is refused
  int min_corners = 8;              // a view with fewer is left out
  double min_rotation_spread = 10;  // deg, the flange's rotation about its least-turned axis (RMS)
  double max_pose_error = 0.5;      // px RMS per pose
};

struct FlangePoseReport {
  std::string label;
  int corners = 0;
  double rms = -1;   // px; -1 when left out
  std::string note;  // why left out or over the limit
};

struct RobotWorldFit {
  bool accepted = false;
  std::string refusal;
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d flange_T_board = Eigen::Isometry3d::Identity();
  double rms = 0;                       // px over every corner used
  double rotation_spread = 0;           // deg
  std::vector<FlangePoseReport> poses;  // one per view, in order
};

// Never throws: an unusable set comes back refused with the reason.
RobotWorldFit fit_robot_world(const std::vector<FlangeView>& views, const CharucoTarget& target,
                              const CameraIntrinsics& camera, const RobotWorldLimits& limits = {});

// The report: the camera's pose (position, roll-pitch-yaw), the board's mount, every pose's error.
std::string describe(const RobotWorldFit& fit, const RobotWorldLimits& limits);

}  // namespace wysiwyf::vision::calibration
