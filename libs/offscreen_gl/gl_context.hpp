#pragma once
// An OpenGL 3.3 core context with no window, through EGL: the GPU's EGL device when there is
// one, Mesa's surfaceless platform (llvmpipe, on the CPU) otherwise. Current on the thread that
// created it; one owner.
#include <string>

namespace wysiwyf::render {

class GlContext {
 public:
  // Throws std::runtime_error saying which EGL step failed and what to install or check.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void make_current();
  const std::string& renderer() const { return renderer_; }  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  const std::string& platform() const { return platform_; }  // "device" or "surfaceless"

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string renderer_, platform_;
};

}  // namespace wysiwyf::render
