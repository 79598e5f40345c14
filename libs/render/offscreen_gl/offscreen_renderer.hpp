#pragma once
// Draws meshes with a pinhole camera into a framebuffer object (colour RGBA8, depth 32F, with
// optional multisampling) and reads back colour (RGB, row 0 at the top as in OpenCV) and metric
// depth. begin() makes its context current on the calling thread (hold a GlContext::Scope around
// a tick's drawing so the context is free again after it).
#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "offscreen_gl/gl_context.hpp"
#include "offscreen_gl/mesh.hpp"
#include "offscreen_gl/pinhole.hpp"

namespace wysiwyf::render {

class OffscreenRenderer {
 public:
  // samples > 1: multisampled anti-aliasing (edges come out with sub-pixel coverage).
  OffscreenRenderer(GlContext& context, const Pinhole& camera, int samples = 1);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  const Pinhole& camera() const { return camera_; }
  int add_mesh(const Mesh& mesh);  // returns the mesh's id

  void begin(const Eigen::Vector4f& clear_rgba);
  // Light from `direction` (camera frame, pointing where the light travels), plus ambient.
  void set_light(const Eigen::Vector3f& direction, float ambient);
  // camera_T_object: the object's pose in the camera (OpenCV) frame. unlit: flat colour.
  void draw(int mesh, const Eigen::Isometry3d& camera_T_object, const Eigen::Vector4f& rgba, bool lit = true);
  // After the draws of a frame.
  void read_rgb(std::vector<std::uint8_t>& rgb);  // width * height * 3
  void read_depth(std::vector<float>& metres);    // width * height; 0 where nothing was drawn

 private:
  void resolve();
  void release_gl_objects();

  GlContext& context_;
  Pinhole camera_;
  int samples_;
  unsigned program_ = 0;
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;  // drawn into (multisampled when samples_ > 1)
  unsigned resolved_fbo_ = 0, resolved_color_ = 0, resolved_depth_ = 0;
  int loc_clip_ = -1, loc_normal_ = -1, loc_color_ = -1, loc_light_ = -1, loc_ambient_ = -1, loc_lit_ = -1;
  struct GpuMesh {
    unsigned vao = 0, vbo = 0;
    int vertices = 0;
  };
  std::vector<GpuMesh> meshes_;
  std::vector<float> scratch_;
  bool resolved_ = false;
};

}  // namespace wysiwyf::render
