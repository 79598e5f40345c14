#include "plate_markers.hpp"

#include <cmath>
#include <stdexcept>

namespace wysiwyf::vision {

PlateMarkers PlateMarkers::from_arm(const robot::ArmModel& model, double lamp_radius) {
  PlateMarkers m;
  m.lamp_radius = lamp_radius;
  // The frames are fixed to the plate: any q will do.
  const robot::JointVector q0 = robot::JointVector::Zero(model.dof());
  const Eigen::Isometry3d dev_T_base = model.fk(q0, model.frame("dev")).inverse();
  for (int i = 0; i < 4; ++i) {
    const std::string name = "marker_" + std::to_string(i);
    m.dev_p[static_cast<std::size_t>(i)] = (dev_T_base * model.fk(q0, model.frame(name))).translation();
    if (std::abs(m.dev_p[static_cast<std::size_t>(i)].z()) > 1e-6)
      throw std::invalid_argument(model.urdf_path() + ": frame " + name + " lies " +
                                  std::to_string(m.dev_p[static_cast<std::size_t>(i)].z()) +
                                  " m off the plate's face (dev z = 0); the tracker expects the lamps on it");
  }
  return m;
}

Eigen::Vector3d PlateMarkers::dome_offset(const Eigen::Vector3d& eye_centre, const Eigen::Vector3d& eye_normal) const {
  if (lamp_radius <= 0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d to_camera = -eye_centre.normalized();
  const double cos_alpha = eye_normal.dot(to_camera);
  const Eigen::Vector3d across = eye_normal - cos_alpha * to_camera;  // the normal as seen in the image plane
  const double sin_alpha = across.norm();
  if (sin_alpha < 1e-9) return Eigen::Vector3d::Zero();
  return (4.0 * lamp_radius / (3.0 * M_PI)) * (1.0 - cos_alpha) / sin_alpha * across;
}

}  // namespace wysiwyf::vision
