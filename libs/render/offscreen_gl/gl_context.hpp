#pragma once
// An OpenGL 3.3 core context with no window, through EGL: the GPU's EGL device when there is
// one, Mesa's surfaceless platform (llvmpipe, on the CPU) otherwise. One owner; current on no
// thread until made current. A context can be current on one thread at a time, and the real
// clock ticks a component on its own thread after activating it on the main one: hold a
// GlContext::Scope around the GL work of a tick, so the context is free again when it ends.
#include <string>

namespace wysiwyf::render {

class GlContext {
 public:
  // Throws std::runtime_error saying which EGL step failed and what to install or check.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void make_current();  // on this thread (nothing to do when it already is)
  void release();       // current on no thread, when it was on this one
  bool is_current() const;

  // Current for the scope's life; released at its end unless it was current already.
  class Scope {
   public:
    explicit Scope(GlContext& context) : context_(context), was_current_(context.is_current()) {
      context_.make_current();
    }
    ~Scope() {
      if (!was_current_) context_.release();
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    GlContext& context_;
    bool was_current_;
  };

  const std::string& renderer() const { return renderer_; }  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  const std::string& platform() const { return platform_; }  // "device" or "surfaceless"

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string renderer_, platform_;
};

}  // namespace wysiwyf::render
