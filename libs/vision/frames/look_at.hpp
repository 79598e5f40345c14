#pragma once
// Where a camera is, from where it stands and what it looks at: base_T_eye in OpenCV's camera
// axes (x right, y down, z forward), as camera_sim places its camera and marker_tracker its
// set-up prior.
#include <Eigen/Geometry>

namespace wysiwyf::vision::frames {

// A camera at `eye` looking at `target` with `up` (base frame) up in the image. Looking along
// `up` itself leaves the roll open: then the image's x axis is base x (or base y when the view is
// along base x).
inline Eigen::Isometry3d look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                 const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ()) {
  const Eigen::Vector3d z = (target - eye).normalized();
  Eigen::Vector3d x = z.cross(up.normalized());
  if (x.norm() < 1e-9) x = std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  x = (x - x.dot(z) * z).normalized();
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  base_T_eye.linear().col(0) = x;
  base_T_eye.linear().col(1) = z.cross(x);
  base_T_eye.linear().col(2) = z;
  base_T_eye.translation() = eye;
  return base_T_eye;
}

}  // namespace wysiwyf::vision::frames
