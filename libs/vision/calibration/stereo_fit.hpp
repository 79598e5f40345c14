#pragma once
// A stereo pair's extrinsics and rectification from views of a ChArUco board seen by both cameras
// at once (cv::stereoCalibrate with each camera's intrinsics fixed, cv::stereoRectify), checked
// by what stereo depth needs of it: after rectification a corner lies on the same image row in
// both views. The epipolar error (the rows' difference, px) is reported per view pair and over all
// corners; a set whose error is over the limit (a camera that moved between views, intrinsics of
// another camera) is refused naming its worst pairs, as is one with too few usable pairs.
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "calibration/board_detection.hpp"
#include "calibration/camera_model.hpp"
#include "calibration/charuco_target.hpp"

namespace wysiwyf::vision::calibration {

struct StereoLimits {
  int min_pairs = 8;               // usable view pairs, fewer is refused
  int min_common = 12;             // corners both cameras found; a pair with fewer is left out
  double max_epipolar_rms = 0.3;   // px over every corner of every used pair
  double max_epipolar_pair = 0.6;  // px RMS of one pair
};

struct StereoFit {
  bool accepted = false;
  std::string refusal;
  Eigen::Isometry3d right_T_left = Eigen::Isometry3d::Identity();  // OpenCV's R, T: left's frame in the right's
  double rms = 0;                                                  // px, stereoCalibrate's reprojection error
  double epipolar_rms = 0, epipolar_max = 0;                       // px, rectified rows of every used corner
  std::vector<double> pair_epipolar;                               // px RMS per input pair (-1: left out)
  int pairs_used = 0;
  cv::Matx33d R1, R2;  // rectifying rotations (each camera's rectification_matrix)
  cv::Matx34d P1, P2;  // rectified projections (projection_matrix; P2(0,3) = -fx * baseline)
};

// Fits from pair i = (left[i], right[i]), images of left_camera.size. Never throws.
StereoFit fit_stereo(const std::vector<BoardDetection>& left, const std::vector<BoardDetection>& right,
                     const CharucoTarget& target, const CameraIntrinsics& left_camera,
                     const CameraIntrinsics& right_camera, const StereoLimits& limits = {});

}  // namespace wysiwyf::vision::calibration
