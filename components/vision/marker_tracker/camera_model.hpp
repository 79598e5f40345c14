#pragma once
// The camera's intrinsics as the tracker uses them: an ideal pinhole (fx, fy, cx, cy) that the
// filter projects through, and OpenCV's lens distortion between ideal and measured pixels
// (no distortion: both are the same and nothing is computed).
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include <Eigen/Core>

namespace wysiwyf::vision {

class CameraModel {
 public:
  // Throws std::invalid_argument when fx or fy is not positive or a number is not finite, or
  // when there are distortion coefficients in a count OpenCV does not know (4, 5, 8, 12, 14).
  CameraModel(double fx, double fy, double cx, double cy, std::vector<double> distortion = {});

  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  bool distorted() const { return distorted_; }

  // Ideal pixel of a point in the camera frame (z > 0).
  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    return {fx_ * p.x() / p.z() + cx_, fy_ * p.y() / p.z() + cy_};
  }
  // Where an ideal pixel appears in the (distorted) image, and back.
  Eigen::Vector2d distort(const Eigen::Vector2d& ideal) const;
  Eigen::Vector2d undistort(const Eigen::Vector2d& measured) const;
  // OpenCV's camera matrix and distortion coefficients (for solvePnP on ideal pixels: no
  // distortion is passed there).
  cv::Matx33d matrix() const { return {fx_, 0, cx_, 0, fy_, cy_, 0, 0, 1}; }

 private:
  double fx_, fy_, cx_, cy_;
  cv::Mat distortion_;
  bool distorted_ = false;
};

}  // namespace wysiwyf::vision
