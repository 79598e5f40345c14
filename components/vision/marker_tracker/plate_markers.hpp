#pragma once
// The four lamp markers of the device plate (paper section 5.1) as the tracker sees them: their
// centres in the `dev` frame (from the robot model), the plate's normal, and the lamps' shape.
// A lamp is a dome (a sphere half sunk in the plate): seen at an angle alpha from the normal its
// outline is half a disc and half an ellipse, whose centroid lies (4 r / 3 pi)(1 - cos alpha)
// from the projected centre, toward the normal's side. That shift (0.3 px at 0.6 m and 30
// degrees) is applied to the prediction instead of being left as a bias.
#include <Eigen/Geometry>

#include <array>
#include <string>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::vision {

struct PlateMarkers {
  std::array<Eigen::Vector3d, 4> dev_p;                   // lamp centres in dev, m
  Eigen::Vector3d dev_normal = Eigen::Vector3d::UnitZ();  // out of the plate's front face
  double lamp_radius = 0.006;                             // m; 0: point-like lamps

  // From the arm's model: frames marker_0..3 relative to dev. Throws std::out_of_range when a
  // frame is missing, and std::invalid_argument (naming the URDF) when a lamp lies off the plate's
  // face (dev z = 0).
  static PlateMarkers from_arm(const robot::ArmModel& model, double lamp_radius);

  // cos of the angle between the plate's normal and the direction from a lamp centre to the
  // camera; <= 0: the plate turns its back on the camera.
  static double facing(const Eigen::Vector3d& eye_centre, const Eigen::Vector3d& eye_normal) {
    return -eye_normal.dot(eye_centre.normalized());
  }
  // Where the centroid of a lamp's image lies relative to its centre's, as an eye-frame
  // displacement of the centre (orthographic approximation: the lamp is small).
  Eigen::Vector3d dome_offset(const Eigen::Vector3d& eye_centre, const Eigen::Vector3d& eye_normal) const;
};

}  // namespace wysiwyf::vision
