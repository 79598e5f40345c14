#include "offscreen_gl/offscreen_renderer.hpp"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace wysiwyf::render {

namespace {

const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 clip_T_object;
uniform mat3 camera_R_object;
out vec3 normal_camera;
void main() {
  normal_camera = camera_R_object * normal;
  gl_Position = clip_T_object * vec4(position, 1.0);
})";

const char* kFragmentShader = R"(#version 330 core
in vec3 normal_camera;
uniform vec4 color;
uniform vec3 light_direction;
uniform float ambient;
uniform int lit;
out vec4 fragment;
void main() {
  if (lit == 0) { fragment = color; return; }
  vec3 n = normalize(normal_camera);
  if (!gl_FrontFacing) n = -n;
  float diffuse = max(dot(n, -light_direction), 0.0);
  fragment = vec4(color.rgb * (ambient + (1.0 - ambient) * diffuse), color.a);
})";

unsigned compile(GLenum kind, const char* source) {
  const unsigned s = glCreateShader(kind);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("GL shader compilation failed: ") + log);
  }
  return s;
}

}  // namespace

OffscreenRenderer::OffscreenRenderer(GlContext& context, const Pinhole& camera, int samples)
    : context_(context), camera_(camera), samples_(samples < 1 ? 1 : samples) {
  GlContext::Scope current(context_);
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (samples_ > max_samples) samples_ = max_samples;  // what this GL can do (llvmpipe: 8)
  const unsigned vs = compile(GL_VERTEX_SHADER, kVertexShader), fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("GL program link failed");
  loc_clip_ = glGetUniformLocation(program_, "clip_T_object");
  loc_normal_ = glGetUniformLocation(program_, "camera_R_object");
  loc_color_ = glGetUniformLocation(program_, "color");
  loc_light_ = glGetUniformLocation(program_, "light_direction");
  loc_ambient_ = glGetUniformLocation(program_, "ambient");
  loc_lit_ = glGetUniformLocation(program_, "lit");

  auto make_target = [&](int samples, unsigned& fbo, unsigned& color, unsigned& depth) {
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_RGBA8, camera_.width,
                                     camera_.height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_DEPTH_COMPONENT32F, camera_.width,
                                     camera_.height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("GL: the " + std::to_string(camera_.width) + "x" + std::to_string(camera_.height) +
                               " framebuffer with " + std::to_string(samples) + " sample(s) is not complete");
  };
  make_target(samples_, fbo_, color_, depth_);
  if (samples_ > 1) make_target(1, resolved_fbo_, resolved_color_, resolved_depth_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // the clip transform flips y, so windings flip: draw both sides
  set_light(Eigen::Vector3f(0.3f, 0.6f, 1.0f).normalized(), 0.35f);
}

OffscreenRenderer::~OffscreenRenderer() {
  // Its GL objects go with the context if that is current elsewhere (a thread that ended with it).
  try {
    GlContext::Scope current(context_);
    release_gl_objects();
  } catch (const std::exception&) {
  }
}

void OffscreenRenderer::release_gl_objects() {
  for (auto& m : meshes_) {
    glDeleteBuffers(1, &m.vbo);
    glDeleteVertexArrays(1, &m.vao);
  }
  for (unsigned rb : {color_, depth_, resolved_color_, resolved_depth_})
    if (rb) glDeleteRenderbuffers(1, &rb);
  for (unsigned fb : {fbo_, resolved_fbo_})
    if (fb) glDeleteFramebuffers(1, &fb);
  glDeleteProgram(program_);
}

int OffscreenRenderer::add_mesh(const Mesh& mesh) {
  GlContext::Scope current(context_);
  GpuMesh g;
  g.vertices = static_cast<int>(mesh.positions.size());
  std::vector<float> interleaved;
  interleaved.reserve(mesh.positions.size() * 6);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    for (const auto* v : {&mesh.positions[i], &mesh.normals[i]})
      interleaved.insert(interleaved.end(), v->data(), v->data() + 3);
  glGenVertexArrays(1, &g.vao);
  glBindVertexArray(g.vao);
  glGenBuffers(1, &g.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)), interleaved.data(),
               GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  glEnableVertexAttribArray(1);
  meshes_.push_back(g);
  return static_cast<int>(meshes_.size()) - 1;
}

void OffscreenRenderer::begin(const Eigen::Vector4f& clear) {
  context_.make_current();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, camera_.width, camera_.height);
  glClearColor(clear.x(), clear.y(), clear.z(), clear.w());
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glUseProgram(program_);
  resolved_ = false;
}

void OffscreenRenderer::set_light(const Eigen::Vector3f& direction, float ambient) {
  GlContext::Scope current(context_);
  glUseProgram(program_);
  const Eigen::Vector3f d = direction.normalized();
  glUniform3f(loc_light_, d.x(), d.y(), d.z());
  glUniform1f(loc_ambient_, ambient);
}

void OffscreenRenderer::draw(int mesh, const Eigen::Isometry3d& camera_T_object, const Eigen::Vector4f& rgba,
                             bool lit) {
  const GpuMesh& g = meshes_.at(static_cast<std::size_t>(mesh));
  // Composed in double, handed to GL in float: sub-millimetre at metres.
  const Eigen::Matrix4f clip = (camera_.clip_from_camera().cast<double>() * camera_T_object.matrix()).cast<float>();
  const Eigen::Matrix3f R = camera_T_object.linear().cast<float>();
  glUniformMatrix4fv(loc_clip_, 1, GL_FALSE, clip.data());
  glUniformMatrix3fv(loc_normal_, 1, GL_FALSE, R.data());
  glUniform4f(loc_color_, rgba.x(), rgba.y(), rgba.z(), rgba.w());
  glUniform1i(loc_lit_, lit ? 1 : 0);
  glBindVertexArray(g.vao);
  glDrawArrays(GL_TRIANGLES, 0, g.vertices);
}

void OffscreenRenderer::resolve() {
  if (samples_ > 1 && !resolved_) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_fbo_);
    glBlitFramebuffer(0, 0, camera_.width, camera_.height, 0, 0, camera_.width, camera_.height, GL_COLOR_BUFFER_BIT,
                      GL_LINEAR);
    glBlitFramebuffer(0, 0, camera_.width, camera_.height, 0, 0, camera_.width, camera_.height, GL_DEPTH_BUFFER_BIT,
                      GL_NEAREST);
  }
  resolved_ = true;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, samples_ > 1 ? resolved_fbo_ : fbo_);
}

void OffscreenRenderer::read_rgb(std::vector<std::uint8_t>& rgb) {
  resolve();
  const std::size_t row = static_cast<std::size_t>(camera_.width) * 3;
  rgb.resize(row * camera_.height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, camera_.width, camera_.height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  // GL's row 0 is the bottom: flip so row 0 is the top.
  std::vector<std::uint8_t> tmp(row);
  for (int y = 0; y < camera_.height / 2; ++y) {
    std::uint8_t* a = &rgb[row * y];
    std::uint8_t* b = &rgb[row * (camera_.height - 1 - y)];
    std::memcpy(tmp.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, tmp.data(), row);
  }
}

void OffscreenRenderer::read_depth(std::vector<float>& metres) {
  resolve();
  const std::size_t w = static_cast<std::size_t>(camera_.width), h = static_cast<std::size_t>(camera_.height);
  scratch_.resize(w * h);
  metres.resize(w * h);
  glReadPixels(0, 0, camera_.width, camera_.height, GL_DEPTH_COMPONENT, GL_FLOAT, scratch_.data());
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const float d = scratch_[(h - 1 - y) * w + x];
      metres[y * w + x] = d >= 1.0f ? 0.0f : static_cast<float>(camera_.depth_from_buffer(d));
    }
}

}  // namespace wysiwyf::render
