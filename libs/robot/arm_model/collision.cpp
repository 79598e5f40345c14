// Collision elements of the URDF as plain primitives, and the point-inside test of each.
#include <cmath>
#include <sstream>

#include "arm_model/urdf_collision.hpp"
#include "puma_model/urdf_parts.hpp"

namespace wysiwyf::robot {

const char* to_string(ShapeType type) {
  switch (type) {
    case ShapeType::kBox: return "box";
    case ShapeType::kCylinder: return "cylinder";
    case ShapeType::kSphere: return "sphere";
    case ShapeType::kMesh: return "mesh";
  }
  return "unknown";
}

bool CollisionShape::contains(const Eigen::Vector3d& p, double tolerance) const {
  switch (type) {
    case ShapeType::kBox: return ((p.cwiseAbs() - 0.5 * box_size).array() <= tolerance).all();
    case ShapeType::kCylinder:
      return std::abs(p.z()) <= 0.5 * length + tolerance && p.head<2>().norm() <= radius + tolerance;
    case ShapeType::kSphere: return p.norm() <= radius + tolerance;
    case ShapeType::kMesh: return false;
  }
  return false;
}

namespace detail {

void collect_collision(const urdf::Link& link, FrameId frame, int body, const Eigen::Isometry3d& body_T_link,
                       std::vector<CollisionShape>& shapes, std::vector<std::string>& notes) {
  for (const urdf::CollisionSharedPtr& element : link.collision_array) {
    if (!element || !element->geometry) continue;
    CollisionShape s;
    s.link = link.name;
    s.frame = frame;
    s.body = body;
    s.link_T_shape = isometry_of(element->origin);
    s.body_T_shape = body_T_link * s.link_T_shape;
    const urdf::Geometry& g = *element->geometry;
    switch (g.type) {
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(g);
        s.type = ShapeType::kBox;
        s.box_size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(g);
        s.type = ShapeType::kCylinder;
        s.radius = cylinder.radius;
        s.length = cylinder.length;
        break;
      }
      case urdf::Geometry::SPHERE:
        s.type = ShapeType::kSphere;
        s.radius = static_cast<const urdf::Sphere&>(g).radius;
        break;
      case urdf::Geometry::MESH: {
        const auto& mesh = static_cast<const urdf::Mesh&>(g);
        s.type = ShapeType::kMesh;
        s.mesh_filename = mesh.filename;
        s.mesh_scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
        std::ostringstream note;
        note << "link '" << link.name << "': collision mesh '" << mesh.filename << "' (scale " << mesh.scale.x << " "
             << mesh.scale.y << " " << mesh.scale.z
             << ") is not supported yet (primitives only: box, cylinder, sphere); the link has no "
                "collision volume from it";
        notes.push_back(note.str());
        break;
      }
    }
    shapes.push_back(std::move(s));
  }
}

}  // namespace detail
}  // namespace wysiwyf::robot
