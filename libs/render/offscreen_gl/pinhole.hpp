#pragma once
// A pinhole camera as OpenCV defines it (x right, y down, z forward; pixel centres at integer
// coordinates, u = fx X/Z + cx), turned into the OpenGL clip transform that rasterises exactly
// there. Distortion is not rendered: images come out undistorted.
#include <cmath>

#include <Eigen/Core>

namespace wysiwyf::render {

struct Pinhole {
  int width = 640, height = 480;
  double fx = 600, fy = 600, cx = 319.5, cy = 239.5;
  double near_m = 0.02, far_m = 20.0;

  // A size of 16..4096 px and a finite K with fx, fy > 0 (what a camera_info must give).
  bool usable() const {
    return width >= 16 && height >= 16 && width <= 4096 && height <= 4096 && fx > 0 && fy > 0 && std::isfinite(fx) &&
           std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy);
  }
  // This camera (its clip planes) with a camera_info's size and row-major K (fx K[0], cx K[2],
  // fy K[4], cy K[5]); check usable() on the result.
  template <class RowMajorK>
  Pinhole with_intrinsics(int w, int h, const RowMajorK& k) const {
    Pinhole c = *this;
    c.width = w, c.height = h;
    c.fx = k[0], c.fy = k[4], c.cx = k[2], c.cy = k[5];
    return c;
  }
  static constexpr const char* kUnusableInfo =
      "a camera_info without a size of 16..4096 px or a finite K with fx, fy > 0";
  bool same_intrinsics(const Pinhole& o) const {
    return width == o.width && height == o.height && fx == o.fx && fy == o.fy && cx == o.cx && cy == o.cy;
  }

  // Clip coordinates from camera coordinates (OpenCV frame). Rows come out bottom-up in GL
  // window space; the renderer flips them on read-back so row 0 is the top, as in OpenCV.
  Eigen::Matrix4f clip_from_camera() const {
    Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
    P(0, 0) = 2 * fx / width;
    P(0, 2) = 2 * (cx + 0.5) / width - 1;
    P(1, 1) = -2 * fy / height;
    P(1, 2) = 1 - 2 * (cy + 0.5) / height;
    P(2, 2) = (far_m + near_m) / (far_m - near_m);
    P(2, 3) = -2 * far_m * near_m / (far_m - near_m);
    P(3, 2) = 1;
    return P.cast<float>();
  }
  // Metric depth (along z) from a depth-buffer value in [0, 1].
  double depth_from_buffer(double d) const {
    const double z_ndc = 2 * d - 1;
    return 2 * far_m * near_m / ((far_m + near_m) - z_ndc * (far_m - near_m));
  }
};

}  // namespace wysiwyf::render
