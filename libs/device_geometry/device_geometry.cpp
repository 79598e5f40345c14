#include "device_geometry/device_geometry.hpp"

#include <string>

namespace wysiwyf::robot {

namespace {

// A capsule's or cylinder's pose between two points: centred, its z along a -> b.
Eigen::Isometry3d segment_pose(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), (b - a).normalized()).toRotationMatrix();
  T.translation() = 0.5 * (a + b);
  return T;
}

constexpr float kLinkRadius[4] = {0.09f, 0.07f, 0.055f, 0.04f};  // pedestal-shoulder, upper arm, forearm, wrist
const Eigen::Vector3d kPedestalFoot(0, 0, -0.6);

}  // namespace

DeviceGeometry::DeviceGeometry(const PumaModel& model) : model_(model), dev_(model.frame("dev")) {
  for (const char* f : {"link1", "link3", "link4", "flange"}) points_.push_back(model.frame(f));
  for (int m = 0; m < 4; ++m) lamps_.push_back(model.frame("marker_" + std::to_string(m)));
  // The links' lengths are constant (rigid): measured once, at q = 0.
  const auto p = joint_points(Vector6d::Zero());
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double length = (p[i + 1] - p[i]).norm();
    if (length <= 1e-3) continue;  // coincident joint origins: nothing to draw
    DeviceShape s;
    s.kind = DeviceShape::Kind::kCapsule;
    s.part = DeviceShape::Part::kLink;
    s.index = static_cast<int>(i);
    s.size = Eigen::Vector3f(kLinkRadius[i], static_cast<float>(length / 2), 0);
    shapes_.push_back(s);
    segments_.push_back(static_cast<int>(i));
  }
  shapes_.push_back({DeviceShape::Kind::kBox, DeviceShape::Part::kPlate, 0, Eigen::Vector3f(0.1f, 0.1f, 0.005f)});
  shapes_.push_back({DeviceShape::Kind::kCylinder, DeviceShape::Part::kKnob, 0, Eigen::Vector3f(0.015f, 0.02f, 0)});
  for (int m = 0; m < 4; ++m)
    shapes_.push_back({DeviceShape::Kind::kSphere, DeviceShape::Part::kLamp, m, Eigen::Vector3f(0.006f, 0, 0)});
}

std::vector<Eigen::Vector3d> DeviceGeometry::joint_points(const Vector6d& q) const {
  std::vector<Eigen::Vector3d> p{kPedestalFoot};
  for (FrameId f : points_) p.push_back(model_.fk(q, f).translation());
  return p;
}

void DeviceGeometry::poses(const Vector6d& q, std::vector<Eigen::Isometry3d>& base_T_shape) const {
  base_T_shape.resize(shapes_.size());
  const auto p = joint_points(q);
  const Eigen::Isometry3d base_T_dev = model_.fk(q, dev_);
  std::size_t k = 0;
  for (int segment : segments_) {
    const auto i = static_cast<std::size_t>(segment);
    base_T_shape[k++] = segment_pose(p[i], p[i + 1]);
  }
  base_T_shape[k] = base_T_dev;
  base_T_shape[k++].translate(Eigen::Vector3d(0, 0, -0.005));  // the plate's front face is dev's z = 0
  base_T_shape[k] = base_T_dev;
  base_T_shape[k++].translate(Eigen::Vector3d(0, 0, 0.02));  // the knob, 4 cm out of the face
  for (FrameId lamp : lamps_) base_T_shape[k++] = model_.fk(q, lamp);
}

}  // namespace wysiwyf::robot
