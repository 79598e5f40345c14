#include "device_geometry/device_geometry.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace wysiwyf::render {

using robot::CollisionShape;
using robot::kMaxArmDof;
using robot::ShapeType;

namespace {

constexpr int kLamps = 4;  // marker_0..3 (arm_model/display_frames.hpp)

// The part a link is, and the lamp's number for marker_<k>.
DeviceShape::Part part_of(const std::string& link, int& index) {
  index = 0;
  if (link == "dev") return DeviceShape::Part::kPlate;
  if (link == "knob") return DeviceShape::Part::kKnob;
  for (int k = 0; k < kLamps; ++k)
    if (link == "marker_" + std::to_string(k)) {
      index = k;
      return DeviceShape::Part::kLamp;
    }
  return DeviceShape::Part::kArm;
}

}  // namespace

DeviceGeometry::DeviceGeometry(const robot::ArmModel& model) : model_(model) {
  for (const CollisionShape& c : model.collision_shapes()) {
    if (!c.supported()) continue;  // a mesh: ArmModel::collision_notes() says so
    DeviceShape s;
    s.link = c.link;
    s.part = part_of(c.link, s.index);
    switch (c.type) {
      case ShapeType::kBox:
        s.kind = DeviceShape::Kind::kBox;
        s.size = (0.5 * c.box_size).cast<float>();
        break;
      case ShapeType::kCylinder:
        s.kind = DeviceShape::Kind::kCylinder;
        s.size = Eigen::Vector3f(static_cast<float>(c.radius), static_cast<float>(0.5 * c.length), 0.0f);
        break;
      case ShapeType::kSphere:
        s.kind = DeviceShape::Kind::kSphere;
        s.size = Eigen::Vector3f(static_cast<float>(c.radius), 0.0f, 0.0f);
        break;
      case ShapeType::kMesh: continue;
    }
    shapes_.push_back(std::move(s));
    bodies_.push_back(c.body);
    body_T_shape_.push_back(c.body_T_shape);
    if (std::find(used_bodies_.begin(), used_bodies_.end(), c.body) == used_bodies_.end())
      used_bodies_.push_back(c.body);
  }
  auto require = [&](const std::string& link, const char* what) {
    const bool found =
        std::any_of(shapes_.begin(), shapes_.end(), [&](const DeviceShape& s) { return s.link == link; });
    if (!found)
      throw std::invalid_argument(model.urdf_path() + ": link '" + link + "' (" + what +
                                  ") has no <collision> box, cylinder or sphere; the camera simulation and the "
                                  "device mask draw the device from them");
  };
  require("dev", "the plate");
  require("knob", "the plate's knob");
  for (int k = 0; k < kLamps; ++k) require("marker_" + std::to_string(k), "a lamp on the plate");
}

void DeviceGeometry::poses(const robot::JointRef& q, std::vector<Eigen::Isometry3d>& base_T_shape) const {
  std::array<Eigen::Isometry3d, kMaxArmDof + 1> base_T_body;  // on the stack: no allocation per call
  for (int body : used_bodies_) base_T_body[static_cast<std::size_t>(body)] = model_.fk(q, model_.body_frame(body));
  base_T_shape.resize(shapes_.size());
  for (std::size_t i = 0; i < shapes_.size(); ++i)
    base_T_shape[i] = base_T_body[static_cast<std::size_t>(bodies_[i])] * body_T_shape_[i];
}

}  // namespace wysiwyf::render
