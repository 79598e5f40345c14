// camera_sim: what the real camera would see (paper section 5.1, Fig. 6a): blue cloth on the
// table and behind it, the arm's links wrapped in blue (the collision shapes of its URDF, posed
// from joint state through the arm model), the aluminium plate with its four lamp markers and the knob, and the user's hand
// (skin, pointing: the index fingertip at the true fingertip pose), optionally with a bright LED
// on the fingertip's nail (the fingertip marker the paper cites for hand tracking); with lighting
// variation, sensor noise, optical blur and blue spill on the hand's edges. Beside the image it
// publishes ground truth for tests and metrics: eye_T_base, eye_T_dev, the hand mask and the
// metric depth; optionally a stereo right image, rectified, with its camera_info (P[3] = -fx B).
#include <array>
#include <deque>
#include <utility>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "offscreen_gl/gl_context.hpp"
#include "offscreen_gl/offscreen_renderer.hpp"
#include "device_geometry/device_mesh.hpp"
#include "frames/look_at.hpp"
#include "image/image_view.hpp"
#include "arm_model/display_frames.hpp"
#include "sensor_effects.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/joint_positions.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::render {

namespace {

const Eigen::Vector4f kCloth(0.10f, 0.16f, 0.62f, 1), kAluminium(0.72f, 0.72f, 0.74f, 1), kLamp(1.0f, 0.97f, 0.85f, 1),
    kSkin(0.86f, 0.62f, 0.50f, 1), kBlack(0, 0, 0, 1), kWhite(1, 1, 1, 1), kMaskDevice(0, 0, 1, 1);

// The hand, in the fingertip's frame (x along the pointing index finger, z out of the back of the
// hand, the origin the fingertip sphere's centre, as arm_sim simulates it): finger segments and
// the palm as (mesh, pose) pairs are laid out once.
constexpr double kFingerRadius = 0.009, kIndexLength = 0.075;
// The LED on the index fingernail (a 5 mm dome): its centre 6 mm behind the fingertip, on the nail.
const Eigen::Vector3d kMarkerOnFinger(-0.006, 0.0, kFingerRadius);

}  // namespace

class CameraSim final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("simulated camera: cloth, blue-wrapped arm, plate with lamps, hand; with ground truth");
    urdf_ = ctx.param<std::string>("urdf", "robots/puma560.urdf",
                                   "the arm's URDF with the display's frames (cwd, then config/)");
    camera_.width = ctx.param<int>("width", 640, "image width, px", Range{16, 1280});
    camera_.height = ctx.param<int>("height", 480, "image height, px", Range{16, 720});
    const auto K =
        ctx.param<std::array<double, 4>>("intrinsics", {600, 600, 319.5, 239.5}, "fx fy cx cy, px", Range{0, 1e5});
    const auto eye = ctx.param<std::array<double, 3>>("eye", {1.3, -0.5, 0.75}, "camera position in the base frame, m");
    const auto target =
        ctx.param<std::array<double, 3>>("look_at", {0.55, 0.0, 0.35}, "where the camera looks, base frame, m");
    path_ =
        ctx.param<std::vector<double>>("path", {}, "moving camera: rows [t s, eye x y z, look_at x y z], times from 0",
                                       std::nullopt, Length::rows_of(7));
    noise_ = ctx.param<double>("noise", 2.0, "sensor noise, grey levels (sigma)", Range{0, 50});
    blur_ = ctx.param<double>("blur", 0.7, "optical blur, px (sigma; 0: none)", Range{0, 5});
    flicker_ = ctx.param<double>("light_variation", 0.04, "relative amplitude of slow lighting changes", Range{0, 0.5});
    spill_ = ctx.param<double>("spill", 0.3, "blue spill on the hand's edges, 0..1", Range{0, 1});
    baseline_ = ctx.param<double>("stereo_baseline", 0.0,
                                  "0: mono; else also render a right camera this far along x, m", Range{0, 1});
    seed_ = ctx.param<int>("seed", 1, "noise seed", Range{0, 1e9});
    plate_cloth_ =
        ctx.param_choice("plate", "aluminium",
                         "the plate as the paper's prototype has it (aluminium), or wrapped in the blue cloth like the "
                         "arm (cloth: the keyer takes it out, the user sees the virtual face; lamps and knob stay)",
                         {"aluminium", "cloth"}) == "cloth";
    marker_ =
        ctx.param<bool>("fingertip_marker", false,
                        "draw a bright LED on the index fingernail (5 mm, 6 mm behind the tip), for fingertip_tracker");
    const auto marker_colour = ctx.param<std::array<double, 3>>(
        "marker_colour", {0.25, 1.0, 0.3}, "the LED's colour, RGB 0..1 (unlit: it glows)", Range{0, 1});
    marker_colour_ = Eigen::Vector4f(static_cast<float>(marker_colour[0]), static_cast<float>(marker_colour[1]),
                                     static_cast<float>(marker_colour[2]), 1);
    hidden_ = ctx.param<std::vector<double>>(
        "hidden_markers", {}, "lamps not drawn (occluded, switched off): rows [t_start s, t_end s, marker 0..3]",
        std::nullopt, Length::rows_of(3));
    exposure_ = ctx.param<double>("exposure", 0.0,
                                  "s the shutter stays open (0: instantaneous); moving things smear over it: the image "
                                  "is the mean of exposure_samples renders at the joint and hand states of their "
                                  "times (ground truth stays at the frame's stamp, the end of the exposure)",
                                  Range{0, 0.1});
    exposure_samples_ = ctx.param<int>("exposure_samples", 8, "renders averaged over the exposure", Range{2, 64});
    // Deep queues: the exposure looks back up to 100 ms into 1 kHz streams.
    joints_in_ = ctx.input<msg::JointState>("joint_state", "the arm's joints", Qos::sensor(128));
    hand_in_ = ctx.input<msg::PoseStamped>(
        "hand_pose", "base_T_fingertip: the index fingertip, the finger along x, the back of the hand along z",
        Qos::sensor(128));
    image_ = ctx.output<msg::Image>("image", "the camera image, rgb8", Qos::sensor(2));
    right_ = ctx.output<msg::Image>("image_right", "the right camera's image (stereo), rgb8", Qos::sensor(2));
    info_ = ctx.output<msg::CameraInfo>("camera_info", "intrinsics (no distortion)", Qos::sensor(2));
    right_info_ = ctx.output<msg::CameraInfo>("camera_info_right", "the right camera's (stereo): P[3] = -fx baseline",
                                              Qos::sensor(2));
    true_eye_T_base_ = ctx.output<msg::PoseStamped>("true_eye_T_base", "ground truth", Qos::sensor(4));
    true_eye_T_dev_ = ctx.output<msg::PoseStamped>("true_eye_T_dev", "ground truth", Qos::sensor(4));
    true_mask_ =
        ctx.output<msg::Image>("true_hand_mask", "ground truth: 255 where the hand is seen, mono8", Qos::sensor(2));
    true_device_mask_ = ctx.output<msg::Image>(
        "true_device_mask", "ground truth: 255 where the device (arm, plate, knob, lamps) is seen, mono8",
        Qos::sensor(2));
    true_depth_ = ctx.output<msg::Image>("true_depth", "ground truth metric depth, 32FC1", Qos::sensor(2));
    camera_.fx = K[0], camera_.fy = K[1], camera_.cx = K[2], camera_.cy = K[3];
    camera_.near_m = 0.05, camera_.far_m = 10;
    if (eye == target) ctx.reject("look_at", "must differ from eye");
    base_T_eye_ = vision::frames::look_at(Eigen::Vector3d(eye[0], eye[1], eye[2]),
                                          Eigen::Vector3d(target[0], target[1], target[2]));
    try {
      model_ = robot::load_display_arm(find_config_file(urdf_), "flange");
      device_ = std::make_unique<DeviceGeometry>(*model_);
      q_ = robot::JointVector::Zero(model_->dof());
    } catch (const std::exception& e) {
      ctx.reject("urdf", e.what());
    }
  }

  void activate() override {
    gl_ = std::make_unique<GlContext>();
    GlContext::Scope gl(*gl_);
    renderer_ = std::make_unique<OffscreenRenderer>(*gl_, camera_, 4);
    renderer_->set_light(Eigen::Vector3f(-0.3f, 0.8f, 0.6f), 0.45f);
    table_ = renderer_->add_mesh(Mesh::box(Eigen::Vector3f(1.0f, 1.0f, 0.025f)));
    backdrop_ = renderer_->add_mesh(Mesh::plane(3.0f, 3.0f));
    palm_ = renderer_->add_mesh(Mesh::box(Eigen::Vector3f(0.045f, 0.042f, 0.014f)));
    index_ =
        renderer_->add_mesh(Mesh::capsule(static_cast<float>(kFingerRadius), static_cast<float>(kIndexLength / 2)));
    curled_ = renderer_->add_mesh(Mesh::capsule(0.0095f, 0.012f));
    thumb_ = renderer_->add_mesh(Mesh::capsule(0.0105f, 0.022f));
    led_ = renderer_->add_mesh(Mesh::sphere(0.005f));
    // The arm and its device (libs/render/device_geometry): a mesh per shape, the sizes are constant.
    for (const auto& shape : device_->shapes()) device_meshes_.push_back(renderer_->add_mesh(device_mesh(shape)));
    effects_ = SensorEffects(
        SensorEffectsParams{noise_, blur_, spill_, cv::Scalar(kCloth.x() * 255, kCloth.y() * 255, kCloth.z() * 255)},
        static_cast<std::uint64_t>(seed_));
  }

  void tick(Time now) override {
    GlContext::Scope gl(*gl_);  // free again after the tick: the next may run on another thread
    auto stamp = [&](const std_msgs::Header& h) { return h.stamp_ns() > 0 ? h.stamp_ns() : now.ns; };
    while (take_checked(joints_in_, joints_msg_)) {
      if (std::string why = msgs::joint_positions(joints_msg_, model_->dof(), q_); !why.empty()) {
        reject(joints_in_, why);
        continue;
      }
      have_joints_ = true;
      if (exposure_ > 0) joint_history_.emplace_back(stamp(joints_msg_.header()), q_);
    }
    while (take_checked(hand_in_, hand_msg_)) {
      const Eigen::Isometry3d T = msgs::to_isometry(hand_msg_.pose());
      base_T_hand_ = T, have_hand_ = true;
      if (exposure_ > 0) hand_history_.emplace_back(stamp(hand_msg_.header()), T);
    }
    const std::int64_t oldest = now.ns - static_cast<std::int64_t>(exposure_ * 1e9) - 1'000'000;
    while (joint_history_.size() > 1 && joint_history_[1].first <= oldest) joint_history_.pop_front();
    while (hand_history_.size() > 1 && hand_history_[1].first <= oldest) hand_history_.pop_front();
    if (start_ns_ < 0) start_ns_ = now.ns;
    const double t = static_cast<double>(now.ns - start_ns_) * 1e-9;
    t_ = t;
    if (!path_.empty()) base_T_eye_ = path_pose(t);
    const Eigen::Isometry3d eye_T_base = base_T_eye_.inverse();
    const double gain = 1.0 + flicker_ * std::sin(2 * M_PI * t / 7.0);

    render(eye_T_base, false);
    renderer_->read_depth(depth_);
    renderer_->read_rgb(rgb_);
    if (exposure_ > 0) expose(now, rgb_, [&](std::int64_t) { return eye_T_base; });
    render(eye_T_base, true);  // the hand white, the device blue, everything else black: the true masks
    renderer_->read_rgb(mask_rgb_);
    cv::Mat mask, device_mask;
    const cv::Mat mask_rgb(camera_.height, camera_.width, CV_8UC3, mask_rgb_.data());
    cv::extractChannel(mask_rgb, mask, 0);
    cv::threshold(mask, mask, 127, 255, cv::THRESH_BINARY);
    cv::extractChannel(mask_rgb, device_mask, 2);
    cv::threshold(device_mask, device_mask, 127, 255, cv::THRESH_BINARY);
    device_mask &= ~mask;
    cv::Mat img(camera_.height, camera_.width, CV_8UC3, rgb_.data());
    effects_.apply(img, mask, gain);
    publish_image(image_, img, "rgb8", now);
    publish_image(true_mask_, mask, "mono8", now);
    publish_image(true_device_mask_, device_mask, "mono8", now);
    publish_image(true_depth_, cv::Mat(camera_.height, camera_.width, CV_32FC1, depth_.data()), "32FC1", now);
    if (baseline_ > 0) {
      Eigen::Isometry3d eye_T_right = Eigen::Isometry3d::Identity();
      eye_T_right.translation().x() = baseline_;
      const Eigen::Isometry3d right_T_base = (base_T_eye_ * eye_T_right).inverse();
      render(right_T_base, false);
      renderer_->read_rgb(right_rgb_);
      if (exposure_ > 0) expose(now, right_rgb_, [&](std::int64_t) { return right_T_base; });
      cv::Mat right_mask;  // the right camera sees the spill on the hand's edges too, from its own view
      if (spill_ > 0) {
        render(right_T_base, true);
        renderer_->read_rgb(mask_rgb_);
        cv::extractChannel(cv::Mat(camera_.height, camera_.width, CV_8UC3, mask_rgb_.data()), right_mask, 0);
        cv::threshold(right_mask, right_mask, 127, 255, cv::THRESH_BINARY);
      }
      cv::Mat right(camera_.height, camera_.width, CV_8UC3, right_rgb_.data());
      effects_.apply(right, right_mask, gain);
      publish_image(right_, right, "rgb8", now);
    }
    // Ground truth and intrinsics.
    fill_header(pose_msg_.header(), now.ns, seq_, "eye");
    pose_msg_.child_frame_id("base");
    msgs::to_msg(eye_T_base, pose_msg_.pose());
    true_eye_T_base_.write(pose_msg_);
    if (have_joints_) {
      pose_msg_.child_frame_id("dev");
      msgs::to_msg(eye_T_base * model_->fk(q_, model_->frame("dev")), pose_msg_.pose());
      true_eye_T_dev_.write(pose_msg_);
    }
    info_msg_.header() = pose_msg_.header();
    info_msg_.width(static_cast<std::uint32_t>(camera_.width)),
        info_msg_.height(static_cast<std::uint32_t>(camera_.height));
    info_msg_.distortion_model("plumb_bob");
    info_msg_.k() = {camera_.fx, 0, camera_.cx, 0, camera_.fy, camera_.cy, 0, 0, 1};
    info_msg_.r() = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    info_msg_.p() = {camera_.fx, 0, camera_.cx, 0, 0, camera_.fy, camera_.cy, 0, 0, 0, 1, 0};
    info_.write(info_msg_);
    if (baseline_ > 0) {
      info_msg_.p()[3] = -camera_.fx * baseline_;
      right_info_.write(info_msg_);
    }
    ++seq_;
  }

  void deactivate() override {
    renderer_.reset();
    gl_.reset();
  }

 private:
  bool lamp_hidden(int marker) const {
    for (std::size_t i = 0; i + 2 < hidden_.size(); i += 3)
      if (t_ >= hidden_[i] && t_ < hidden_[i + 1] && static_cast<int>(hidden_[i + 2]) == marker) return true;
    return false;
  }

  Eigen::Isometry3d path_pose(double t) const {
    const std::size_t rows = path_.size() / 7;
    std::size_t i = 0;
    while (i + 1 < rows && path_[7 * (i + 1)] <= t) ++i;
    const double* a = &path_[7 * i];
    const double* b = &path_[7 * std::min(i + 1, rows - 1)];
    const double s = (b[0] > a[0]) ? std::clamp((t - a[0]) / (b[0] - a[0]), 0.0, 1.0) : 0.0;
    auto lerp = [&](int k) {
      return Eigen::Vector3d(a[k] + s * (b[k] - a[k]), a[k + 1] + s * (b[k + 1] - a[k + 1]),
                             a[k + 2] + s * (b[k + 2] - a[k + 2]));
    };
    return vision::frames::look_at(lerp(1), lerp(4));
  }

  // One pass of the scene; mask_pass: unlit, the hand white, the device blue, everything else black.
  void render(const Eigen::Isometry3d& eye_T_base, bool mask_pass) {
    auto color = [&](const Eigen::Vector4f& c, bool is_hand) { return mask_pass ? (is_hand ? kWhite : kBlack) : c; };
    auto device_color = [&](const Eigen::Vector4f& c) { return mask_pass ? kMaskDevice : c; };
    renderer_->begin(mask_pass ? Eigen::Vector4f(0, 0, 0, 1) : kCloth * 0.8f);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.6, 0, -0.025);
    renderer_->draw(table_, eye_T_base * T, color(kCloth, false), !mask_pass);
    // Cloth hanging behind the table, facing the camera (the plane's normal z turned to -x).
    Eigen::Isometry3d back(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()));
    back.translation() = Eigen::Vector3d(1.8, 0, 0.5);
    renderer_->draw(backdrop_, eye_T_base * back, color(kCloth, false), !mask_pass);
    if (have_joints_) {
      device_->poses(q_, device_poses_);
      for (std::size_t i = 0; i < device_poses_.size(); ++i) {
        const DeviceShape& shape = device_->shapes()[i];
        const Eigen::Isometry3d eye_T_shape = eye_T_base * device_poses_[i];
        switch (shape.part) {
          case DeviceShape::Part::kArm:
            renderer_->draw(device_meshes_[i], eye_T_shape, device_color(kCloth), !mask_pass);
            break;
          case DeviceShape::Part::kPlate:
            renderer_->draw(device_meshes_[i], eye_T_shape, device_color(plate_cloth_ ? kCloth : kAluminium),
                            !mask_pass);
            break;
          case DeviceShape::Part::kKnob:
            renderer_->draw(device_meshes_[i], eye_T_shape, device_color(kAluminium), !mask_pass);
            break;
          case DeviceShape::Part::kLamp:
            if (!lamp_hidden(shape.index)) renderer_->draw(device_meshes_[i], eye_T_shape, device_color(kLamp), false);
            break;
        }
      }
    }
    if (have_hand_) {
      // A pointing hand: the index finger out along x to the fingertip at the origin, the palm
      // behind it, the other three fingers curled under the palm's front edge, the thumb along it.
      const Eigen::Isometry3d eye_T_tip = eye_T_base * base_T_hand_;
      const Eigen::Matrix3d along_x = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
      auto at = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = R, T.translation() = p;
        return eye_T_tip * T;
      };
      const double palm_front = -kIndexLength - 0.004;
      renderer_->draw(index_, at({-kIndexLength / 2, 0, 0}, along_x), color(kSkin, true), !mask_pass);
      renderer_->draw(palm_, at({palm_front - 0.045, 0.032, -0.004}), color(kSkin, true), !mask_pass);
      for (int f = 1; f <= 3; ++f)  // curled: pointing down (-z) from the palm's front edge
        renderer_->draw(curled_, at({palm_front - 0.004, 0.02 * f, -0.022}), color(kSkin, true), !mask_pass);
      renderer_->draw(thumb_, at({palm_front - 0.02, -0.018, -0.01}, along_x), color(kSkin, true), !mask_pass);
      if (marker_)  // glowing: unlit; not hand in the mask (the keyer sees it as a light, like the lamps)
        renderer_->draw(led_, at(kMarkerOnFinger), mask_pass ? kBlack : marker_colour_, false);
    }
  }

  // The colour image averaged over the exposure: exposure_samples renders at the middles of equal
  // slices of [now - exposure, now], each with the arm and hand as they were then (the latest
  // state stamped at or before it) and the camera pose view(t). The current state is restored.
  template <class View>
  void expose(Time now, std::vector<std::uint8_t>& rgb, View view) {
    const robot::JointVector q_now = q_;
    const Eigen::Isometry3d hand_now = base_T_hand_;
    exposure_sum_.create(camera_.height, camera_.width, CV_32FC3);
    exposure_sum_.setTo(0);
    for (int k = 0; k < exposure_samples_; ++k) {
      const double before = exposure_ * (1.0 - (k + 0.5) / exposure_samples_);
      const std::int64_t t = now.ns - static_cast<std::int64_t>(std::llround(before * 1e9));
      q_ = state_at(joint_history_, t, q_now);
      base_T_hand_ = state_at(hand_history_, t, hand_now);
      render(view(t), false);
      renderer_->read_rgb(sample_rgb_);
      cv::accumulate(cv::Mat(camera_.height, camera_.width, CV_8UC3, sample_rgb_.data()), exposure_sum_);
    }
    q_ = q_now;
    base_T_hand_ = hand_now;
    exposure_sum_.convertTo(cv::Mat(camera_.height, camera_.width, CV_8UC3, rgb.data()), CV_8UC3,
                            1.0 / exposure_samples_);
  }
  template <class T>
  static T state_at(const std::deque<std::pair<std::int64_t, T>>& history, std::int64_t t, const T& fallback) {
    const T* found = history.empty() ? &fallback : &history.front().second;
    for (const auto& [stamp, value] : history)
      if (stamp <= t) found = &value;
    return *found;
  }

  void publish_image(Output<msg::Image>& out, const cv::Mat& m, const char* encoding, Time now) {
    cv::Mat pixels = vision::image::allocate(out_msg_, m.cols, m.rows, encoding);
    m.copyTo(pixels);  // (same size and type: into the message's buffer)
    fill_header(out_msg_.header(), now.ns, seq_, "eye");
    out.write(out_msg_);
  }

  std::string urdf_;
  Pinhole camera_;
  std::vector<double> path_, hidden_;
  double t_ = 0;  // seconds since the first tick
  double noise_ = 2, blur_ = 0.7, flicker_ = 0.04, spill_ = 0.3, baseline_ = 0;
  int seed_ = 1;
  Eigen::Isometry3d base_T_eye_ = Eigen::Isometry3d::Identity(), base_T_hand_ = Eigen::Isometry3d::Identity();
  std::unique_ptr<robot::ArmModel> model_;
  std::unique_ptr<GlContext> gl_;
  std::unique_ptr<OffscreenRenderer> renderer_;
  int table_ = -1, backdrop_ = -1, palm_ = -1, index_ = -1, curled_ = -1, thumb_ = -1, led_ = -1;
  bool marker_ = false, plate_cloth_ = false;
  Eigen::Vector4f marker_colour_ = kWhite;
  std::unique_ptr<DeviceGeometry> device_;
  std::vector<int> device_meshes_;
  std::vector<Eigen::Isometry3d> device_poses_;
  robot::JointVector q_;
  bool have_joints_ = false, have_hand_ = false;
  std::int64_t start_ns_ = -1;
  std::uint64_t seq_ = 0;
  SensorEffects effects_;
  std::vector<std::uint8_t> rgb_, mask_rgb_, right_rgb_, sample_rgb_;
  double exposure_ = 0;
  int exposure_samples_ = 8;
  std::deque<std::pair<std::int64_t, robot::JointVector>> joint_history_;
  std::deque<std::pair<std::int64_t, Eigen::Isometry3d>> hand_history_;
  cv::Mat exposure_sum_;
  std::vector<float> depth_;
  msg::JointState joints_msg_;
  msg::PoseStamped hand_msg_, pose_msg_;
  msg::Image out_msg_;
  msg::CameraInfo info_msg_;
  Input<msg::JointState> joints_in_;
  Input<msg::PoseStamped> hand_in_;
  Output<msg::Image> image_, right_, true_mask_, true_device_mask_, true_depth_;
  Output<msg::CameraInfo> info_, right_info_;
  Output<msg::PoseStamped> true_eye_T_base_, true_eye_T_dev_;
};

}  // namespace wysiwyf::render

WYSIWYF_COMPONENT(wysiwyf::render::CameraSim, "camera_sim")
