#pragma once
// Triangle meshes with per-vertex normals, and the primitives the scenes use.
#include <Eigen/Core>

#include <vector>

namespace wysiwyf::render {

struct Mesh {
  std::vector<Eigen::Vector3f> positions;  // three per triangle
  std::vector<Eigen::Vector3f> normals;    // one per position

  static Mesh box(const Eigen::Vector3f& half_extents);
  static Mesh plane(float half_x, float half_y);  // z = 0, normal +z
  static Mesh sphere(float radius, int slices = 24, int stacks = 16);
  static Mesh capsule(float radius, float half_length, int slices = 24, int stacks = 16);  // along z
  static Mesh cylinder(float radius, float half_length, int slices = 24);                  // along z
};

}  // namespace wysiwyf::render
