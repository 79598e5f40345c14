#include "calibration/robot_world_poses.hpp"

#include <cmath>

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
  std::uniform_real_distribution<double> u01(0, 1);
  const cv::Matx33d& K = camera.camera_matrix;
  const Eigen::Vector3d centre(target.width() / 2, target.height() / 2, 0);
  // The board facing the camera, read the right way up (see dev_T_board).
  const Eigen::Matrix3d facing = target.texture_y_flipped() ? Eigen::Matrix3d(Eigen::Vector3d(1, -1, -1).asDiagonal())
                                                            : Eigen::Matrix3d::Identity();
  std::vector<robot::JointVector> out;
  robot::JointVector q = q_home;
  for (int tries = 0; static_cast<int>(out.size()) < count && tries < 200 * count; ++tries) {
    const double z = 0.75 + 0.3 * u01(rng);
    const double px = camera.size.width * (0.25 + 0.5 * u01(rng)), py = camera.size.height * (0.25 + 0.5 * u01(rng));
    const Eigen::Vector3d at(z * (px - K(0, 2)) / K(0, 0), z * (py - K(1, 2)) / K(1, 1), z);
    const double axis = 2 * M_PI * u01(rng), tilt = (15 + 20 * u01(rng)) * M_PI / 180;
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(axis), std::sin(axis), 0)).toRotationMatrix() *
        Eigen::AngleAxisd((u01(rng) - 0.5) * M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix() * facing;
    Eigen::Isometry3d eye_T_board = Eigen::Isometry3d::Identity();
    eye_T_board.linear() = R;
    eye_T_board.translation() = at - R * centre;
    bool inside = true;
    for (const cv::Point2f& p : project(camera, eye_T_board, target.corners()))
      inside = inside && p.x > 10 && p.y > 10 && p.x < camera.size.width - 10 && p.y < camera.size.height - 10;
    if (!inside) continue;
    const Eigen::Isometry3d base_T_flange = base_T_eye * eye_T_board * flange_T_board.inverse();
    const robot::ArmIkResult ik = arm.ik_nearest(base_T_flange, q, flange);
    if (!ik.ok()) continue;
    q = ik.q;
    out.push_back(ik.q);
  }
  return out;
}

}  // namespace wysiwyf::vision::calibration
