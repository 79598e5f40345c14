#pragma once
// The PUMA and its device as a camera sees them: a capsule per segment between the joint
// origins (pedestal foot, link1, link3, link4, flange), the plate (a 20 x 20 x 1 cm box whose
// front face is dev's z = 0), the knob on it, and the plate's four lamps. One list of shapes with
// constant sizes, posed for any joint angles: what camera_sim draws as the real arm, and what
// device_mask renders to tell the device from the hand.
#include <vector>

#include <Eigen/Geometry>

#include "puma_model/puma_model.hpp"

namespace wysiwyf::robot {

struct DeviceShape {
  enum class Kind { kCapsule, kBox, kCylinder, kSphere };
  enum class Part { kLink, kPlate, kKnob, kLamp };
  Kind kind = Kind::kBox;
  Part part = Part::kLink;
  int index = 0;  // the link segment 0..3, or the lamp 0..3
  // kCapsule, kCylinder: (radius, half length along z, 0); kBox: half extents; kSphere: (radius, 0, 0).
  Eigen::Vector3f size = Eigen::Vector3f::Zero();
};

class DeviceGeometry {
 public:
  explicit DeviceGeometry(const PumaModel& model);

  const std::vector<DeviceShape>& shapes() const { return shapes_; }
  // Each shape's pose in base at joint angles q (its centre; capsules and cylinders along z), in
  // the order of shapes().
  void poses(const Vector6d& q, std::vector<Eigen::Isometry3d>& base_T_shape) const;

 private:
  std::vector<Eigen::Vector3d> joint_points(const Vector6d& q) const;

  const PumaModel& model_;
  FrameId dev_;
  std::vector<FrameId> points_, lamps_;
  std::vector<DeviceShape> shapes_;
  std::vector<int> segments_;  // the joint-point segment of each link shape
};

}  // namespace wysiwyf::robot
