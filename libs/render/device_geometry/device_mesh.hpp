#pragma once
// A device shape as an offscreen_gl mesh (for the components that draw the device; they link
// wysiwyf_offscreen_gl themselves).
#include "device_geometry/device_geometry.hpp"
#include "offscreen_gl/mesh.hpp"

namespace wysiwyf::render {

inline Mesh device_mesh(const DeviceShape& s) {
  switch (s.kind) {
    case DeviceShape::Kind::kCylinder: return Mesh::cylinder(s.size.x(), s.size.y());
    case DeviceShape::Kind::kSphere: return Mesh::sphere(s.size.x());
    case DeviceShape::Kind::kBox: break;
  }
  return Mesh::box(s.size);
}

}  // namespace wysiwyf::render
