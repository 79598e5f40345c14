#pragma once
// Where a board is put in front of a camera for a calibration view: its centre on the ray through
// an image point at a depth, facing the camera the right way up (a y-up board turned over about
// x), tilted about an in-plane axis and spun about the view axis; drawn at random (seeded) within
// ranges, and kept when its points land inside the image. The simulated views (board_view_sim)
// and the robot-world pose set (robot_world_poses) place their boards so.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "calibration/camera_model.hpp"
#include "calibration/charuco_target.hpp"

namespace wysiwyf::vision::calibration {

struct BoardPlacement {
  double u = 0, v = 0;  // px, where the board's centre is seen
  double depth = 0.5;   // m along the optical axis
  double axis = 0;      // rad, direction of the tilt's in-plane axis
  double tilt = 0;      // rad
  double spin = 0;      // rad about the view axis
};

struct PlacementRanges {
  double image_margin = 0.15;           // of the image's size kept clear of the centre's draw on each side
  double near = 0.3, far = 0.6;         // m
  double min_tilt = 15, max_tilt = 45;  // deg
  double max_spin = 30;                 // deg either way
};

inline BoardPlacement random_placement(const CameraIntrinsics& camera, const PlacementRanges& r, std::mt19937& rng) {
  std::uniform_real_distribution<double> u01(0, 1);
  BoardPlacement p;
  p.depth = r.near + (r.far - r.near) * u01(rng);
  p.u = camera.size.width * (r.image_margin + (1 - 2 * r.image_margin) * u01(rng));
  p.v = camera.size.height * (r.image_margin + (1 - 2 * r.image_margin) * u01(rng));
  p.axis = 2 * M_PI * u01(rng);
  p.tilt = (r.min_tilt + (r.max_tilt - r.min_tilt) * u01(rng)) * M_PI / 180;
  p.spin = (u01(rng) - 0.5) * 2 * r.max_spin * M_PI / 180;
  return p;
}

inline Eigen::Isometry3d eye_T_board(const CharucoTarget& target, const CameraIntrinsics& camera,
                                     const BoardPlacement& p) {
  const cv::Matx33d& K = camera.camera_matrix;
  const Eigen::Vector3d at(p.depth * (p.u - K(0, 2)) / K(0, 0), p.depth * (p.v - K(1, 2)) / K(1, 1), p.depth);
  const Eigen::Matrix3d facing = target.texture_y_flipped() ? Eigen::Matrix3d(Eigen::Vector3d(1, -1, -1).asDiagonal())
                                                            : Eigen::Matrix3d::Identity();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(p.tilt, Eigen::Vector3d(std::cos(p.axis), std::sin(p.axis), 0)).toRotationMatrix() *
               Eigen::AngleAxisd(p.spin, Eigen::Vector3d::UnitZ()).toRotationMatrix() * facing;
  T.translation() = at - T.linear() * Eigen::Vector3d(target.width() / 2, target.height() / 2, 0);
  return T;
}

// Whether every point (board frame) projects at least `margin` px inside the image.
inline bool inside_image(const CameraIntrinsics& camera, const Eigen::Isometry3d& eye_T_board,
                         const std::vector<cv::Point3f>& points, double margin) {
  for (const cv::Point2f& p : project(camera, eye_T_board, points))
    if (!(p.x > margin && p.y > margin && p.x < camera.size.width - margin && p.y < camera.size.height - margin))
      return false;
  return true;
}

}  // namespace wysiwyf::vision::calibration
