#pragma once
// A point seen by a rectified stereo pair (the right camera displaced by the baseline B along the
// left one's x): from its left pixel (u, v) and the right image's column u_r, depth Z = fx B / d
// with the disparity d = u - u_r, and X, Y through the left pinhole; its covariance from the
// centroids' noise through that triangulation (first order).
#include <optional>

#include <Eigen/Core>

namespace wysiwyf::vision {

struct StereoCamera {
  double fx = 0, fy = 0, cx = 0, cy = 0;  // the left (rectified) camera's, px
  double baseline = 0;                    // m
};

struct StereoPoint {
  Eigen::Vector3d eye_p = Eigen::Vector3d::Zero();       // m, left camera frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // m^2, left camera axes
};

// Empty when the disparity is not positive (at or beyond infinity).
std::optional<StereoPoint> triangulate(const StereoCamera& camera, double u, double v, double u_right,
                                       double pixel_sigma);

}  // namespace wysiwyf::vision
