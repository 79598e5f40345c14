#include "hand_point.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace wysiwyf::vision {
namespace {

using Points = std::vector<Eigen::Vector3f>::iterator;

// The centroid of [begin, end).
Eigen::Vector3d centroid(Points begin, Points end) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto it = begin; it != end; ++it) sum += it->cast<double>();
  return sum / static_cast<double>(end - begin);
}

// How wide [begin, end) is across `axis`: the RMS distance of its points from their centroid,
// the component along the axis taken out.
double width_across(Points begin, Points end, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d c = centroid(begin, end);
  double sum = 0;
  for (auto it = begin; it != end; ++it) {
    const Eigen::Vector3d d = it->cast<double>() - c;
    sum += (d - d.dot(axis) * axis).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(end - begin));
}

// The tip of a finger pointing out of the hand [begin, end) (reordered), if one does: the hand's
// ends along its principal axis, a twentieth of its points each (a finger holds about a sixth of
// a hand's visible surface); the one less than kFingerWidth as wide as the other is a finger
// (1.8 cm across against a 8-9 cm palm), and its last `fraction` of the points is the tip.
std::optional<Eigen::Vector3d> fingertip(Points begin, Points end, double fraction) {
  // (RMS widths: a finger's end 6-7 mm against the palm's 11-29 mm in the stereo tests' views, a
  // ratio of 0.2-0.6; a hand's two ends alike are not told apart)
  constexpr double kFingerWidth = 0.7;
  const Eigen::Vector3d mean = centroid(begin, end);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (auto it = begin; it != end; ++it) {
    const Eigen::Vector3d d = it->cast<double>() - mean;
    scatter += d * d.transpose();
  }
  const Eigen::Vector3d axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(2);
  const auto along = [&](const Eigen::Vector3f& p) { return axis.dot(p.cast<double>() - mean); };
  const auto n = end - begin;
  const auto end_count = std::max<std::ptrdiff_t>(3, n / 20);
  if (2 * end_count >= n) return std::nullopt;
  std::sort(begin, end, [&](const Eigen::Vector3f& a, const Eigen::Vector3f& b) { return along(a) < along(b); });
  const double low = width_across(begin, begin + end_count, axis), high = width_across(end - end_count, end, axis);
  const auto count = std::max<std::ptrdiff_t>(1, static_cast<std::ptrdiff_t>(std::ceil(fraction * n)));
  if (high < kFingerWidth * low) return centroid(end - count, end);
  if (low < kFingerWidth * high) return centroid(begin, begin + count);
  return std::nullopt;
}

}  // namespace

std::optional<HandPoint> estimate_hand_point(const cv::Mat& depth, const cv::Mat& alpha, const Intrinsics& K,
                                             const HandPointOptions& options, const Eigen::Isometry3d* dev_T_eye,
                                             std::vector<Eigen::Vector3f>& scratch) {
  // Pixels with depth under the matte, back-projected (eye frame), less the device's.
  scratch.clear();
  const Eigen::Isometry3f dev_T_eye_f = dev_T_eye ? dev_T_eye->cast<float>() : Eigen::Isometry3f::Identity();
  const Eigen::AlignedBox3f device = options.device_box.cast<float>();
  const float fx = static_cast<float>(K.fx), fy = static_cast<float>(K.fy), cx = static_cast<float>(K.cx),
              cy = static_cast<float>(K.cy);
  for (int v = 0; v < depth.rows; ++v) {
    const float* z = depth.ptr<float>(v);
    const std::uint8_t* a = alpha.ptr<std::uint8_t>(v);
    for (int u = 0; u < depth.cols; ++u) {
      if (a[u] < options.min_alpha || !(z[u] > 0) || !std::isfinite(z[u])) continue;
      const Eigen::Vector3f p((static_cast<float>(u) - cx) * z[u] / fx, (static_cast<float>(v) - cy) * z[u] / fy, z[u]);
      if (dev_T_eye && device.contains(dev_T_eye_f * p)) continue;
      scratch.push_back(p);
    }
  }
  if (static_cast<int>(scratch.size()) < options.min_pixels) return std::nullopt;
  const auto by_depth = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) { return a.z() < b.z(); };
  const auto middle = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
  std::nth_element(scratch.begin(), middle, scratch.end(), by_depth);
  const double median = middle->z();
  const auto inliers_end = std::partition(scratch.begin(), scratch.end(), [&](const Eigen::Vector3f& p) {
    return std::abs(p.z() - median) <= options.band;
  });
  const auto inliers = inliers_end - scratch.begin();
  if (inliers < options.min_pixels) return std::nullopt;
  if (options.point == HandPointOptions::Point::kTip) {
    if (const auto tip = fingertip(scratch.begin(), inliers_end, options.tip_fraction))
      return HandPoint{*tip, static_cast<int>(inliers), median, true};
  }
  auto used_end = inliers_end;
  if (options.point == HandPointOptions::Point::kNearest) {
    const auto count = std::max<std::ptrdiff_t>(
        1, static_cast<std::ptrdiff_t>(std::ceil(options.nearest_fraction * static_cast<double>(inliers))));
    std::nth_element(scratch.begin(), scratch.begin() + (count - 1), inliers_end, by_depth);
    used_end = scratch.begin() + count;
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto it = scratch.begin(); it != used_end; ++it) sum += it->cast<double>();
  const auto used = used_end - scratch.begin();
  return HandPoint{sum / static_cast<double>(used), static_cast<int>(used), median};
}

}  // namespace wysiwyf::vision
