#pragma once
// What a CameraInfo says of a pinhole camera, checked once for every reader: its intrinsics (K)
// and, for the right camera of a rectified pair, the baseline (P[3] = -fx B, as ROS and OpenCV
// write it).
#include <cmath>
#include <optional>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::msgs {

struct CameraIntrinsics {
  int width = 0, height = 0;  // px
  double fx = 0, fy = 0, cx = 0, cy = 0;
};

// None unless fx, fy are finite and > 0 and cx, cy finite.
inline std::optional<CameraIntrinsics> intrinsics(const msg::CameraInfo& info) {
  const auto& k = info.k();
  if (!(k[0] > 0 && k[4] > 0 && std::isfinite(k[0]) && std::isfinite(k[4]) && std::isfinite(k[2]) &&
        std::isfinite(k[5])))
    return std::nullopt;
  return CameraIntrinsics{static_cast<int>(info.width()), static_cast<int>(info.height()), k[0], k[4], k[2], k[5]};
}

// The baseline B (m) of the right camera of a rectified pair; none unless P[0] > 0 and P[3] < 0.
inline std::optional<double> stereo_baseline(const msg::CameraInfo& right) {
  const double fx = right.p()[0], tx = right.p()[3];
  if (!(fx > 0 && tx < 0 && std::isfinite(fx) && std::isfinite(tx))) return std::nullopt;
  return -tx / fx;
}

}  // namespace wysiwyf::msgs
