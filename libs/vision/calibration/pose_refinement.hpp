#pragma once
// The robot-world fit's last step: base_T_eye and flange_T_board adjusted together so that every
// board corner of every view projects where it was seen (Levenberg-Marquardt on a 12-vector of
// small rotations and translations applied on the right of each transform, central differences).
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "calibration/camera_model.hpp"

namespace wysiwyf::vision::calibration {

struct PoseObservations {
  Eigen::Isometry3d base_T_flange;
  std::vector<cv::Point3f> board_points;  // m, board frame
  std::vector<cv::Point2f> seen;          // px
};

// Refines both transforms in place; returns each view's RMS reprojection error (px).
std::vector<double> refine_robot_world(const std::vector<PoseObservations>& views, const CameraIntrinsics& camera,
                                       Eigen::Isometry3d& base_T_eye, Eigen::Isometry3d& flange_T_board);

// Each view's RMS reprojection error (px) for the given transforms.
std::vector<double> reprojection_errors(const std::vector<PoseObservations>& views, const CameraIntrinsics& camera,
                                        const Eigen::Isometry3d& base_T_eye, const Eigen::Isometry3d& flange_T_board);

}  // namespace wysiwyf::vision::calibration
