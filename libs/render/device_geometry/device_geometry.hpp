#pragma once
// The arm and its device as a camera sees them: every box, cylinder and sphere of the arm's URDF
// <collision> elements (meshes are not loaded), each posed for joint angles q as
// fk(q, its link's frame) * link_T_shape, and told apart as the plate (link `dev`), its knob
// (`knob`), its four lamps (`marker_0..3`) or the arm (every other link: pedestal, links, wrist
// sensor). What camera_sim draws as the real arm, and what device_mask renders to tell the device
// from the hand; any serial arm whose URDF has the display's frames.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::render {

struct DeviceShape {
  enum class Kind { kBox, kCylinder, kSphere };
  enum class Part { kArm, kPlate, kKnob, kLamp };
  Kind kind = Kind::kBox;
  Part part = Part::kArm;
  int index = 0;     // kLamp: the lamp's number k (link marker_k); else 0
  std::string link;  // the URDF link that carries it
  // kCylinder: (radius, half length along z, 0); kBox: half extents; kSphere: (radius, 0, 0).
  Eigen::Vector3f size = Eigen::Vector3f::Zero();
};

class DeviceGeometry {
 public:
  // The shapes of `model`'s collision elements; the model outlives the geometry. Throws
  // std::invalid_argument naming the URDF when the plate (dev), the knob or a lamp (marker_0..3)
  // has no box, cylinder or sphere to draw.
  explicit DeviceGeometry(const robot::ArmModel& model);

  const std::vector<DeviceShape>& shapes() const { return shapes_; }
  // Each shape's pose in base at joint angles q (model.dof() values; its centre, cylinders along
  // z), in the order of shapes().
  void poses(const robot::JointRef& q, std::vector<Eigen::Isometry3d>& base_T_shape) const;

 private:
  const robot::ArmModel& model_;
  std::vector<DeviceShape> shapes_;
  std::vector<int> bodies_;                      // the moving body (0..n) each shape is fixed to
  std::vector<Eigen::Isometry3d> body_T_shape_;  // its pose in that body's frame
  std::vector<int> used_bodies_;                 // the bodies that carry a shape, each once
};

}  // namespace wysiwyf::render
