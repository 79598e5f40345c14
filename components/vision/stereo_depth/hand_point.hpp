#pragma once
// One 3D point for the hand from a depth image and the keyer's alpha: the pixels that are hand
// (alpha) and have a depth, back-projected through the pinhole; those inside the device's box are
// dropped when its pose is known (the keyer keeps the plate, its lamps and knob: they are not
// blue); those farther than `band` from the median depth of the rest too (cloth seen through the
// matte's edge, mismatches); then the centroid of what is left (the visible surface's centre),
// the centroid of its nearest fraction (the part of the hand closest to the camera), or the
// pointing fingertip: along the hand's longest axis (its points' principal direction), the end
// whose cross-section is the thinner by far is a finger, and the centroid of the last tip_fraction
// of the points there is its tip (a hand with no finger out: the centroid).
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <optional>
#include <vector>

namespace wysiwyf::vision {

struct Intrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
};

struct HandPointOptions {
  enum class Point { kCentroid, kNearest, kTip };
  Point point = Point::kCentroid;
  double nearest_fraction = 0.1;
  double tip_fraction = 0.03;      // of the inliers: the fingertip's
  double band = 0.08;              // m either side of the median depth
  int min_alpha = 128;             // 0..255: from this alpha a pixel is hand
  int min_pixels = 300;            // fewer hand pixels with depth: no estimate
  Eigen::AlignedBox3d device_box;  // dev frame, m: what is in it is device, not hand
};

struct HandPoint {
  Eigen::Vector3d eye_p_hand;  // m, eye frame
  int pixels = 0;              // inliers used
  double median_depth = 0;     // m
  bool tip = false;            // the point is a fingertip (Point::kTip found a finger)
};

// depth: CV_32FC1 (0: unknown); alpha: CV_8UC1, same size; dev_T_eye: the device's pose, when
// known. scratch is reused between calls.
std::optional<HandPoint> estimate_hand_point(const cv::Mat& depth, const cv::Mat& alpha, const Intrinsics& K,
                                             const HandPointOptions& options, const Eigen::Isometry3d* dev_T_eye,
                                             std::vector<Eigen::Vector3f>& scratch);

}  // namespace wysiwyf::vision
