#pragma once
// Reading a URDF link's <collision> elements into CollisionShapes (internal to the library).
#include <string>
#include <vector>

#include <urdf_model/link.h>

#include "arm_model/collision_shape.hpp"

namespace wysiwyf::robot::detail {

// Appends the link's collision elements to `shapes` (posed in the link's and the body's frame),
// and one line per element the model cannot use yet (a mesh) to `notes`.
void collect_collision(const urdf::Link& link, FrameId frame, int body, const Eigen::Isometry3d& body_T_link,
                       std::vector<CollisionShape>& shapes, std::vector<std::string>& notes);

}  // namespace wysiwyf::robot::detail
