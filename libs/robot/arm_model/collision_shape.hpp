#pragma once
// The URDF's collision elements as plain data: per link, its primitives (box, cylinder, sphere)
// with their origin. Meshes are recorded (file, scale) but not loaded yet: supported() is false
// for them, and ArmModel::collision_notes() says so per mesh.
#include <string>

#include <Eigen/Geometry>

#include "puma_model/types.hpp"

namespace wysiwyf::robot {

enum class ShapeType { kBox, kCylinder, kSphere, kMesh };

// A readable name of the shape type.
const char* to_string(ShapeType type);

struct CollisionShape {
  std::string link;  // the URDF link that carries it
  FrameId frame;     // that link's frame in the model
  int body = 0;      // the moving body (0 = base) the link is fixed to
  ShapeType type = ShapeType::kBox;
  Eigen::Isometry3d link_T_shape = Eigen::Isometry3d::Identity();  // the <collision><origin>
  Eigen::Isometry3d body_T_shape = Eigen::Isometry3d::Identity();  // the same in the body frame
  Eigen::Vector3d box_size = Eigen::Vector3d::Zero();              // box: full edge lengths along the shape's x, y, z
  double radius = 0.0;                                             // cylinder, sphere [m]
  double length = 0.0;                                             // cylinder: along the shape's z, centred [m]
  std::string mesh_filename;                                       // mesh: as written in the URDF
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();

  // Whether the model can use the shape (every primitive; not a mesh yet).
  bool supported() const { return type != ShapeType::kMesh; }
  // Whether a point given in the shape's own frame lies inside (or on) the primitive; false for a mesh.
  bool contains(const Eigen::Vector3d& shape_p, double tolerance = 0.0) const;
};

}  // namespace wysiwyf::robot
