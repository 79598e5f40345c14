#include "calibration/robot_world_poses.hpp"

#include <cmath>

#include "calibration/board_placement.hpp"

namespace wysiwyf::vision::calibration {

Eigen::Isometry3d dev_T_board(const CharucoTarget& target) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const double w = target.width() / 2, h = target.height() / 2;
  if (target.texture_y_flipped()) {  // board z out of the face, y up the print
    T.translation() = Eigen::Vector3d(-w, -h, 0);
  } else {  // board z into the face, y down the print
    T.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
    T.translation() = Eigen::Vector3d(-w, h, 0);
  }
  return T;
}

std::vector<robot::JointVector> robot_world_poses(const robot::ArmModel& arm, const Eigen::VectorXd& q_home,
                                                  robot::FrameId flange, const Eigen::Isometry3d& flange_T_board,
                                                  const Eigen::Isometry3d& base_T_eye, const CameraIntrinsics& camera,
                                                  const CharucoTarget& target, int count, std::mt19937& rng) {
  PlacementRanges ranges;
  ranges.image_margin = 0.25, ranges.near = 0.75, ranges.far = 1.05, ranges.min_tilt = 15, ranges.max_tilt = 35;
  std::vector<robot::JointVector> out;
  robot::JointVector q = q_home;
  for (int tries = 0; static_cast<int>(out.size()) < count && tries < 200 * count; ++tries) {
    const Eigen::Isometry3d eye_T_board =
        calibration::eye_T_board(target, camera, random_placement(camera, ranges, rng));
    if (!inside_image(camera, eye_T_board, target.corners(), 10)) continue;
    const Eigen::Isometry3d base_T_flange = base_T_eye * eye_T_board * flange_T_board.inverse();
    const robot::ArmIkResult ik = arm.ik_nearest(base_T_flange, q, flange);
    if (!ik.ok()) continue;
    q = ik.q;
    out.push_back(ik.q);
  }
  return out;
}

}  // namespace wysiwyf::vision::calibration
