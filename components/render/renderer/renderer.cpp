// renderer: the virtual environment as the user should see it (paper section 2.2, STEP 1): the
// scene's static bodies and the dynamic bodies at the poses the simulation publishes, with the
// knobs the scene declares on them, drawn from the tracked camera pose eye_T_base with the
// camera's own intrinsics (its camera_info: the rendered and the filmed image are one camera's),
// so that eye_T_v_obj = eye_T_dev (eq. 4) and eye_T_v_env = eye_T_base (eq. 6). Publishes colour
// and metric depth, at the camera's size.
#include <array>
#include <cmath>
#include <cstring>
#include <map>

#include "image/image_view.hpp"
#include "offscreen_gl/gl_context.hpp"
#include "offscreen_gl/offscreen_renderer.hpp"
#include "scene/scene.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::render {

class Renderer final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("draws the virtual environment from the tracked camera pose: colour and metric depth");
    scene_path_ = ctx.param<std::string>("scene", "scenes/cube_on_table.yaml", "scene file (cwd, then config/)");
    camera_.near_m = ctx.param<double>("near", 0.02, "near clipping distance, m", Range{1e-4, 10});
    camera_.far_m = ctx.param<double>("far", 20.0, "far clipping distance, m", Range{0.1, 1000});
    samples_ = ctx.param<int>(
        "samples", 1,
        "multisampling (anti-aliasing) samples; each more costs render time (scripts/bench render measures it)",
        Range{1, 16});
    background_ =
        ctx.param<std::array<double, 3>>("background", {0.08, 0.09, 0.12}, "background colour, RGB 0..1", Range{0, 1});
    eye_T_base_in_ = ctx.input<msg::PoseStamped>("eye_T_base", "where the camera is (the tracker)", Qos::sensor(4));
    info_in_ = ctx.input<msg::CameraInfo>("camera_info", "the camera's size and intrinsics (K; images undistorted)",
                                          Qos::sensor(2));
    objects_in_ =
        ctx.input<msg::ObjectState>("objects", "dynamic bodies of the virtual environment", Qos::reliable(64));
    color_out_ = ctx.output<msg::Image>(
        "color", "the rendered scene, rgb8, stamped with eye_T_base's stamp (the camera frame it is drawn for)",
        Qos::sensor(2));
    depth_out_ =
        ctx.output<msg::Image>("depth", "metric depth along the optical axis, 32FC1 (0: nothing)", Qos::sensor(2));
    if (camera_.near_m >= camera_.far_m)
      ctx.reject("far", "must be larger than near (" + std::to_string(camera_.near_m) + " m)");
    try {
      scene_ = haptics::load_scene(find_config_file(scene_path_));
    } catch (const std::exception& e) {
      ctx.reject("scene", e.what());
    }
  }

  void activate() override {
    gl_ = std::make_unique<GlContext>();
    log("OpenGL on " + gl_->renderer() + " (" + gl_->platform() + ")");
    for (std::size_t i = 0; i < scene_.models.size(); ++i)
      base_T_body_[scene_.models[i].name] = haptics::pose_of(scene_.initial[i]);
  }

  void tick(Time now) override {
    GlContext::Scope gl(*gl_);  // free again after the tick: the next may run on another thread
    if (info_in_.take_latest(info_msg_)) take_camera_info();
    while (take_checked(eye_T_base_in_, pose_msg_))
      eye_T_base_ = msgs::to_isometry(pose_msg_.pose()), have_pose_ = true, pose_stamp_ = pose_msg_.header().stamp_ns();
    while (take_checked(objects_in_, object_msg_))
      base_T_body_[object_msg_.child_frame_id().c_str()] = msgs::to_isometry(object_msg_.pose());
    if (!renderer_)
      return warn_once("no camera_info",
                       "no camera_info yet: nothing is drawn until the camera's "
                       "intrinsics arrive");
    if (!have_pose_) return;  // nothing to draw from yet
    renderer_->begin(Eigen::Vector4f(static_cast<float>(background_[0]), static_cast<float>(background_[1]),
                                     static_cast<float>(background_[2]), 1));
    for (std::size_t i = 0; i < scene_.models.size(); ++i) {
      const auto& m = scene_.models[i];
      const Eigen::Vector4f color =
          m.dynamic ? Eigen::Vector4f(0.85f, 0.55f, 0.15f, 1) : Eigen::Vector4f(0.45f, 0.42f, 0.38f, 1);
      renderer_->draw(meshes_[i], eye_T_base_ * base_T_body_[m.name], color);
    }
    // The knobs: a cylinder from the face out to the knob's tip.
    for (const auto& [body, obj_T_knob] : knobs_)
      renderer_->draw(knob_mesh_, eye_T_base_ * base_T_body_[scene_.models[body].name] * obj_T_knob,
                      Eigen::Vector4f(0.75f, 0.72f, 0.68f, 1));
    renderer_->read_rgb(rgb_);
    renderer_->read_depth(depth_);
    std::memcpy(vision::image::allocate(color_msg_, camera_.width, camera_.height, "rgb8").data, rgb_.data(),
                rgb_.size());
    std::memcpy(vision::image::allocate(depth_msg_, camera_.width, camera_.height, "32FC1").data, depth_.data(),
                depth_.size() * sizeof(float));
    // Stamped with the camera frame its eye_T_base was measured in: the frame it is drawn for.
    const std::int64_t stamp = pose_stamp_ ? pose_stamp_ : now.ns;
    fill_header(color_msg_.header(), stamp, seq_, "eye");
    fill_header(depth_msg_.header(), stamp, seq_++, "eye");
    color_out_.write(color_msg_);
    depth_out_.write(depth_msg_);
  }

  // A new size or new intrinsics: a renderer for them (the meshes again: they live in it).
  void take_camera_info() {
    const Pinhole camera = camera_.with_intrinsics(static_cast<int>(info_msg_.width()),
                                                   static_cast<int>(info_msg_.height()), info_msg_.k());
    if (!camera.usable()) return reject(info_in_, Pinhole::kUnusableInfo);
    for (double d : info_msg_.d())
      if (d != 0.0) {
        warn_once("distorted",
                  "camera_info has lens distortion: the scene is drawn for a pinhole camera, so the "
                  "camera's images should be undistorted (camera: undistort: true)");
        break;
      }
    if (renderer_ && camera.same_intrinsics(camera_)) return;
    camera_ = camera;
    renderer_ = std::make_unique<OffscreenRenderer>(*gl_, camera_, samples_);
    meshes_.clear();
    for (const auto& m : scene_.models) meshes_.push_back(renderer_->add_mesh(Mesh::box(m.half_extents.cast<float>())));
    knobs_.clear();
    const double length = scene_.device.knob_offset.z();
    for (const auto& f : scene_.features) {
      if (f.kind != haptics::DisplayFeature::Kind::kKnob || length <= 0) continue;
      Eigen::Isometry3d obj_T_knob = f.obj_T_plate;
      obj_T_knob.translate(Eigen::Vector3d(0, 0, length / 2));
      knobs_.emplace_back(static_cast<std::size_t>(f.body), obj_T_knob);
      knob_radius_ = f.knob_radius;
    }
    if (!knobs_.empty())
      knob_mesh_ =
          renderer_->add_mesh(Mesh::cylinder(static_cast<float>(knob_radius_), static_cast<float>(length / 2)));
  }

  void deactivate() override {
    renderer_.reset();
    gl_.reset();
  }

 private:
  std::string scene_path_;
  Pinhole camera_;
  int samples_ = 4;
  std::array<double, 3> background_{};
  haptics::Scene scene_;
  std::unique_ptr<GlContext> gl_;
  std::unique_ptr<OffscreenRenderer> renderer_;
  std::vector<int> meshes_;
  std::vector<std::pair<std::size_t, Eigen::Isometry3d>> knobs_;  // body, obj_T_knob (the cylinder's centre)
  int knob_mesh_ = -1;
  double knob_radius_ = 0.015;
  std::map<std::string, Eigen::Isometry3d> base_T_body_;
  Eigen::Isometry3d eye_T_base_ = Eigen::Isometry3d::Identity();
  bool have_pose_ = false;
  std::int64_t pose_stamp_ = 0;  // eye_T_base's: the camera frame it was measured in
  std::uint64_t seq_ = 0;
  std::vector<std::uint8_t> rgb_;
  std::vector<float> depth_;
  msg::PoseStamped pose_msg_;
  msg::CameraInfo info_msg_;
  Input<msg::CameraInfo> info_in_;
  msg::ObjectState object_msg_;
  msg::Image color_msg_, depth_msg_;
  Input<msg::PoseStamped> eye_T_base_in_;
  Input<msg::ObjectState> objects_in_;
  Output<msg::Image> color_out_, depth_out_;
};

}  // namespace wysiwyf::render

WYSIWYF_COMPONENT(wysiwyf::render::Renderer, "renderer")
