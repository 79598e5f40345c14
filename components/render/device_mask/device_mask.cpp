// device_mask: where the real device is in the camera image, from its geometry (the robot model
// and libs/render/device_geometry: the collision shapes of the arm's URDF), the measured joints and the camera's pose: the device's metric depth
// per pixel (0 where it is not). The compositor keeps the device out of the real layer with it
// and lets depth decide only between the hand and the virtual scene: the real plate, knob, lamps
// and arm never show through a virtual surface, while a finger in front of the plate still does.
// Rendered for the image the camera pose belongs to: at eye_T_base's stamp, with the joint state
// nearest that stamp.
#include <cmath>
#include <cstring>
#include <deque>

#include "device_geometry/device_mesh.hpp"
#include "image/image_view.hpp"
#include "offscreen_gl/gl_context.hpp"
#include "offscreen_gl/offscreen_renderer.hpp"
#include "arm_model/display_frames.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/joint_positions.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::render {

class DeviceMask final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("the real device's depth in the camera image, from the robot model, the joints and the camera pose");
    urdf_ = ctx.param<std::string>("urdf", "robots/puma560.urdf", "robot description (as the arm's)");
    camera_.near_m = ctx.param<double>("near", 0.02, "near clipping distance, m", Range{1e-4, 10});
    camera_.far_m = ctx.param<double>("far", 20.0, "far clipping distance, m", Range{0.1, 1000});
    grow_ = ctx.param<double>("grow", 0.004,
                              "m added to every shape's size: the model's and the joints' error, the image's blur",
                              Range{0, 0.1});
    joints_in_ = ctx.input<msg::JointState>("joint_state", "the arm's measured joints", Qos::sensor(128));
    eye_T_base_in_ =
        ctx.input<msg::PoseStamped>("eye_T_base", "where the camera is (stamped with its image)", Qos::sensor(4));
    info_in_ = ctx.input<msg::CameraInfo>("camera_info", "the camera's size and intrinsics", Qos::sensor(2));
    depth_out_ = ctx.output<msg::Image>(
        "depth", "the device's metric depth along the optical axis, 32FC1, 0 where the device is not", Qos::sensor(2));
    if (camera_.near_m >= camera_.far_m) ctx.reject("far", "must be larger than near");
    try {
      model_ = robot::load_display_arm(find_config_file(urdf_), "flange");
      device_ = std::make_unique<DeviceGeometry>(*model_);
    } catch (const std::exception& e) {
      ctx.reject("urdf", e.what());
    }
  }

  void activate() override { gl_ = std::make_unique<GlContext>(); }
  void deactivate() override {
    renderer_.reset();
    gl_.reset();
  }

  void tick(Time now) override {
    GlContext::Scope gl(*gl_);  // free again after the tick: the next may run on another thread
    if (info_in_.take_latest(info_msg_)) take_camera_info();
    while (take_checked(joints_in_, joints_msg_)) {
      JointSample sample{joints_msg_.header().stamp_ns() ? joints_msg_.header().stamp_ns() : now.ns, {}};
      if (std::string why = msgs::joint_positions(joints_msg_, model_->dof(), sample.q); !why.empty()) {
        reject(joints_in_, why);
        continue;
      }
      joints_.push_back(sample);
    }
    while (joints_.size() > 1 && joints_.front().t < now.ns - 1'000'000'000) joints_.pop_front();
    bool fresh = false;
    while (take_checked(eye_T_base_in_, pose_msg_)) {
      const Eigen::Isometry3d T = msgs::to_isometry(pose_msg_.pose());
      eye_T_base_ = T, pose_stamp_ = pose_msg_.header().stamp_ns() ? pose_msg_.header().stamp_ns() : now.ns;
      fresh = true;
    }
    if (!renderer_) return warn_once("no camera_info yet: no device depth until the camera's intrinsics arrive");
    if (!fresh || joints_.empty()) return;
    // The joints nearest the image's time.
    const JointSample* q = &joints_.front();
    for (const auto& s : joints_)
      if (std::abs(s.t - pose_stamp_) < std::abs(q->t - pose_stamp_)) q = &s;
    device_->poses(q->q, poses_);
    renderer_->begin(Eigen::Vector4f(0, 0, 0, 1));
    for (std::size_t i = 0; i < poses_.size(); ++i)
      renderer_->draw(meshes_[i], eye_T_base_ * poses_[i], Eigen::Vector4f(1, 1, 1, 1), false);
    renderer_->read_depth(depth_);
    std::memcpy(vision::image::allocate(depth_msg_, camera_.width, camera_.height, "32FC1").data, depth_.data(),
                depth_.size() * sizeof(float));
    fill_header(depth_msg_.header(), pose_stamp_, seq_++, "eye");
    depth_out_.write(depth_msg_);
  }

 private:
  struct JointSample {
    std::int64_t t = 0;
    robot::JointVector q;
  };

  void take_camera_info() {
    const Pinhole camera = camera_.with_intrinsics(static_cast<int>(info_msg_.width()),
                                                   static_cast<int>(info_msg_.height()), info_msg_.k());
    if (!camera.usable()) return reject(info_in_, Pinhole::kUnusableInfo);
    if (renderer_ && camera.same_intrinsics(camera_)) return;
    camera_ = camera;
    renderer_ = std::make_unique<OffscreenRenderer>(*gl_, camera_, 1);
    meshes_.clear();
    const float grow = static_cast<float>(grow_);
    for (DeviceShape shape : device_->shapes()) {
      shape.size.x() += grow;  // radius or half extent
      if (shape.kind == DeviceShape::Kind::kBox) shape.size += Eigen::Vector3f(0, grow, grow);
      if (shape.kind == DeviceShape::Kind::kCylinder) shape.size.y() += grow;
      meshes_.push_back(renderer_->add_mesh(device_mesh(shape)));
    }
  }

  std::string urdf_;
  double grow_ = 0.004;
  Pinhole camera_;
  std::unique_ptr<robot::ArmModel> model_;
  std::unique_ptr<DeviceGeometry> device_;
  std::unique_ptr<GlContext> gl_;
  std::unique_ptr<OffscreenRenderer> renderer_;
  std::vector<int> meshes_;
  std::vector<Eigen::Isometry3d> poses_;
  std::deque<JointSample> joints_;
  Eigen::Isometry3d eye_T_base_ = Eigen::Isometry3d::Identity();
  std::int64_t pose_stamp_ = 0;
  std::uint64_t seq_ = 0;
  std::vector<float> depth_;
  msg::JointState joints_msg_;
  msg::PoseStamped pose_msg_;
  msg::CameraInfo info_msg_;
  msg::Image depth_msg_;
  Input<msg::JointState> joints_in_;
  Input<msg::PoseStamped> eye_T_base_in_;
  Input<msg::CameraInfo> info_in_;
  Output<msg::Image> depth_out_;
};

}  // namespace wysiwyf::render

WYSIWYF_COMPONENT(wysiwyf::render::DeviceMask, "device_mask")
