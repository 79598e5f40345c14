#include "offscreen_gl/gl_context.hpp"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>

#include <stdexcept>
#include <vector>

namespace wysiwyf::render {

namespace {

std::string egl_error(const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", eglGetError());
  return std::string("EGL: ") + what + " failed (error " + code + ")";
}

// The first EGL device that initialises (a GPU), else the surfaceless Mesa display.
EGLDisplay open_display(std::string& platform) {
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display)
    throw std::runtime_error("EGL: eglGetPlatformDisplayEXT is missing; install libegl1 and libegl-mesa0");
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_device_string =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (query_devices) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (query_devices(8, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        // Mesa's software device is not a GPU: leave it to the surfaceless path.
        const char* ext = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : nullptr;
        if (ext && std::string(ext).find("EGL_MESA_device_software") != std::string::npos) continue;
        EGLDisplay d = get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
          platform = "device";
          return d;
        }
      }
    }
  }
  EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor))
    throw std::runtime_error(egl_error("initialising the surfaceless Mesa display") +
                             "; install libegl-mesa0 and libgl1-mesa-dri");
  platform = "surfaceless";
  return d;
}

}  // namespace

GlContext::GlContext() {
  EGLDisplay display = open_display(platform_);
  display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(egl_error("eglBindAPI(OpenGL)"));
  const EGLint attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  // Rendering goes to framebuffer objects: no config and no surface are needed.
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) throw std::runtime_error(egl_error("creating an OpenGL 3.3 core context"));
  context_ = context;
  make_current();
  renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  release();
}

GlContext::~GlContext() {
  if (context_) {
    release();
    eglDestroyContext(display_, context_);
  }
}

bool GlContext::is_current() const { return context_ && eglGetCurrentContext() == context_; }

void GlContext::make_current() {
  if (is_current()) return;
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
    throw std::runtime_error(egl_error("eglMakeCurrent") + " (is the context current on another thread?)");
}

void GlContext::release() {
  if (is_current()) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace wysiwyf::render
