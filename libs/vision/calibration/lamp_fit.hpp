#pragma once
// The plate's lamp positions relative to the flange (what tracking mode's marker tracker matches
// the camera's image against: the URDF's marker_* links), from a fixed camera watching the lamps
// while the arm moves through poses (robot_world_poses): one least-squares fit of the camera's pose
// in the base frame and every lamp's position on the flange to every lamp's centroid in every image
// (Levenberg-Marquardt on the reprojection error, from the nominal lamps and the camera's pose by
// solvePnP over them). A set that sees a lamp in too few poses, or whose fit leaves a pose over the
// error limit, is refused naming it.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "calibration/camera_model.hpp"

namespace wysiwyf::vision::calibration {

struct LampView {
  std::string label;                             // "pose 3" in reports
  Eigen::Isometry3d base_T_flange;               // the arm's forward kinematics at the pose
  std::vector<std::optional<cv::Point2d>> lamp;  // px, lamp i's centroid; nullopt: not seen
};

struct LampLimits {
  int min_views = 10;           // views, fewer is refused
  int min_views_per_lamp = 6;   // views seeing each lamp
  double max_view_error = 1.0;  // px RMS of a view's lamps after the fit
};

struct LampFit {
  bool accepted = false;
  std::string refusal;
  std::vector<Eigen::Vector3d> flange_p_lamp;  // m, lamp i on the flange
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  double rms = 0;                // px over every observation
  std::vector<double> view_rms;  // px per view (-1: no lamp seen)
};

// Fits from the views, the camera's intrinsics and the nominal lamps (their count is the lamps'),
// the camera's pose with them (a pose held from `calibrate camera-base` would carry its own error
// into every lamp: 0.02 deg is 0.35 mm at a metre). Never throws.
LampFit fit_lamps(const std::vector<LampView>& views, const CameraIntrinsics& camera,
                  const std::vector<Eigen::Vector3d>& nominal_flange_p_lamp, const LampLimits& limits = {});

}  // namespace wysiwyf::vision::calibration
