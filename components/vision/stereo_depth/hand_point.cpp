#include "hand_point.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::vision {

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
  auto used_end = inliers_end;
  if (options.nearest) {
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
