#include "stereo_point.hpp"

namespace wysiwyf::vision {

std::optional<StereoPoint> triangulate(const StereoCamera& c, double u, double v, double u_right, double pixel_sigma) {
  const double d = u - u_right;
  if (!(d > 0) || c.baseline <= 0) return std::nullopt;
  const double z = c.fx * c.baseline / d;
  StereoPoint p;
  p.eye_p = Eigen::Vector3d((u - c.cx) * z / c.fx, (v - c.cy) * z / c.fy, z);
  // d(X, Y, Z) / d(u, v, u_right): Z falls as u rises (dZ/du = -Z/d) and rises with u_right.
  const double dz_du = -z / d, dz_dur = z / d;
  Eigen::Matrix3d J;
  J << z / c.fx + (u - c.cx) / c.fx * dz_du, 0, (u - c.cx) / c.fx * dz_dur,  //
      (v - c.cy) / c.fy * dz_du, z / c.fy, (v - c.cy) / c.fy * dz_dur,       //
      dz_du, 0, dz_dur;
  p.covariance = pixel_sigma * pixel_sigma * J * J.transpose();
  return p;
}

}  // namespace wysiwyf::vision
