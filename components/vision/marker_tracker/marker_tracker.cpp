// marker_tracker: where the camera is (paper section 2.2 STEP 1 and section 5.1): the four lamps
// on the device plate, found in search windows around where the filter predicts them, drive an
// extended Kalman filter on eye_T_base in which the device's motion (joint state through the
// arm's model, any serial arm's URDF) is a known input. Publishes eye_T_base (eq. 6: where the virtual environment is
// drawn), eye_T_dev (eq. 4: where the virtual object is drawn), their covariances, and what it
// saw. `device_motion: state` is the paper's first prototype for comparison: the filter tracks
// eye_T_dev and the robot's motion disturbs the background.
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string_view>
#include <optional>

#include "camera_model.hpp"
#include "joint_history.hpp"
#include "plate_tracker.hpp"
#include "frames/look_at.hpp"
#include "image/image_view.hpp"
#include "arm_model/display_frames.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/joint_positions.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision {

class MarkerTracker final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("camera pose from the plate's four lamps: EKF on eye_T_base with the robot's motion as a known input");
    const auto urdf =
        ctx.param<std::string>("urdf", "robots/puma560.urdf", "the arm's URDF with frames dev and marker_0..3");
    intrinsics_ =
        ctx.param<std::vector<double>>("intrinsics", {}, "fx fy cx cy, px (no distortion); empty: from camera_info",
                                       Range{0, 1e5}, Length::exactly_or_empty(4));
    const auto motion = ctx.param_choice("device_motion", "input",
                                         "input: the filter's state is eye_T_base, the device's motion a known input; "
                                         "state: the state is eye_T_dev (the paper's first prototype, for comparison)",
                                         {"input", "state"});
    TrackerSettings s;
    s.device_motion = motion == "state" ? DeviceMotion::kState : DeviceMotion::kInput;
    s.detector.threshold = ctx.param<int>("threshold", 215, "luma (0..255) above which a pixel is lamp", Range{1, 254});
    s.detector.min_area = ctx.param<int>("min_area", 3, "smallest lamp blob, px", Range{1, 10000});
    s.detector.max_area = ctx.param<int>("max_area", 4000, "largest lamp blob, px", Range{1, 100000});
    const double lamp_radius =
        ctx.param<double>("lamp_radius", 0.006, "radius of the lamps' domes, m (0: points)", Range{0, 0.05});
    s.noise.pixel = ctx.param<double>("pixel_sigma", 0.1, "a lamp centroid's noise, px", Range{0.01, 20});
    // The camera's motion. The default suits a camera on a stand that is moved now and then (the
    // paper's LCD/camera platform): the filter averages over seconds, which the plate's small
    // size needs (a 1 mrad tilt of the plate moves its lamps by 0.04 px at 0.6 m). A moved camera
    // outruns it, is lost and found again by PnP; a head-worn camera wants about 1 and 2.
    s.noise.accel =
        ctx.param<double>("accel_noise", 3e-4, "the camera's acceleration, m/s^2 per sqrt(Hz)", Range{1e-7, 100});
    s.noise.angular_accel = ctx.param<double>(
        "angular_accel_noise", 3e-4, "the camera's angular acceleration, rad/s^2 per sqrt(Hz)", Range{1e-7, 1000});
    // How long the camera's velocity lasts: it moves in short motions (a head turning, a stand
    // nudged) and is still in between. A velocity that persisted would carry the estimate along
    // the line of sight, which four lamps on a small plate pin least.
    s.noise.velocity_time = ctx.param<double>(
        "velocity_time", 0.2, "how long the camera's velocity lasts (correlation time), s; 0: constant velocity",
        Range{0, 1000});
    s.device_accel = ctx.param<double>("device_accel_noise", 1.0,
                                       "device_motion: state only: the device's acceleration the filter must absorb, "
                                       "m/s^2 per sqrt(Hz)",
                                       Range{0, 1000});
    s.device_angular_accel = ctx.param<double>(
        "device_angular_accel_noise", 2.0,
        "device_motion: state only: the device's angular acceleration, rad/s^2 per sqrt(Hz)", Range{0, 10000});
    // Whatever the lamps say, the camera cannot move faster than this: a fix that would move it
    // farther since the last trusted estimate is refused (a head's top speed and turn rate).
    s.motion.max_speed =
        ctx.param<double>("max_camera_speed", 1.0, "the camera's top speed, m/s: a fix that moves it faster is refused",
                          Range{0.01, 100});
    s.motion.max_turn_rate = ctx.param<double>(
        "max_camera_turn_rate", 3.0, "the camera's top turn rate, rad/s: a fix that turns it faster is refused",
        Range{0.01, 1000});
    s.gate = ctx.param<double>(
        "gate", 13.8, "Mahalanobis gate, chi-square with 2 dof (13.8: 99.9 %; a huge value: no gate)", Range{1, 1e12});
    s.min_markers = ctx.param<int>("min_markers", 2, "lamps an image needs to update the filter", Range{1, 4});
    s.lost_after =
        ctx.param<int>("lost_after", 5, "images with too few lamps before the plate is lost", Range{1, 10000});
    s.min_window = ctx.param<int>("min_window", 10, "search window half size at least, px", Range{2, 1000});
    s.max_window = ctx.param<int>("max_window", 80, "search window half size at most, px", Range{2, 1000});
    const auto up =
        ctx.param<std::array<double, 3>>("up", {0, 0, 1}, "the base axis that points up in the image at the first fix");
    const auto prior_eye = ctx.param<std::vector<double>>(
        "prior_eye", {},
        "where the camera roughly is (base frame, m), to start from fewer than four lamps; empty: none", std::nullopt,
        Length::exactly_or_empty(3));
    const auto prior_look_at =
        ctx.param<std::vector<double>>("prior_look_at", {}, "where it looks (base frame, m), with prior_eye",
                                       std::nullopt, Length::exactly_or_empty(3));
    const auto prior_sigma =
        ctx.param<std::array<double, 2>>("prior_sigma", {0.02, 0.02}, "how well: m, rad", Range{1e-6, 10});
    s.acquisition.max_rms_px =
        ctx.param<double>("max_fix_rms", 2.0, "a PnP fix must reproject within this, px", Range{0.01, 100});
    image_in_ = ctx.input<msg::Image>("image", "camera image: rgb8, bgr8 or mono8", Qos::sensor(2));
    info_in_ = ctx.input<msg::CameraInfo>("camera_info", "intrinsics and distortion (unless `intrinsics` is set)",
                                          Qos::sensor(2).optional_input());
    joints_in_ = ctx.input<msg::JointState>("joint_state", "the arm's joints: the device's motion", Qos::sensor(64));
    eye_T_base_out_ =
        ctx.output<msg::PoseStamped>("eye_T_base", "where the robot base is seen from the camera", Qos::sensor(4));
    eye_T_dev_out_ =
        ctx.output<msg::PoseStamped>("eye_T_dev", "where the device plate is seen from the camera", Qos::sensor(4));
    base_cov_out_ = ctx.output<msg::PoseWithCovariance>("eye_T_base_covariance",
                                                        "eye_T_base with its covariance (eye axes)", Qos::sensor(4));
    dev_cov_out_ = ctx.output<msg::PoseWithCovariance>("eye_T_dev_covariance",
                                                       "eye_T_dev with its covariance (eye axes)", Qos::sensor(4));
    markers_out_ =
        ctx.output<msg::MarkerObservation>("markers", "matched lamps and tracking status, every image", Qos::sensor(4));
    s.up_in_base = Eigen::Vector3d(up[0], up[1], up[2]);
    if (s.up_in_base.norm() < 1e-9) ctx.reject("up", "expected a non-zero vector");
    if (s.min_window > s.max_window) ctx.reject("max_window", "must not be below min_window");
    if (s.detector.min_area > s.detector.max_area) ctx.reject("max_area", "must not be below min_area");
    if (prior_eye.size() != prior_look_at.size())
      ctx.reject("prior_look_at", "give prior_eye and prior_look_at together");
    if (prior_eye.size() == 3 && prior_look_at.size() == 3) {
      const Eigen::Vector3d eye(prior_eye[0], prior_eye[1], prior_eye[2]),
          at(prior_look_at[0], prior_look_at[1], prior_look_at[2]);
      if ((at - eye).norm() < 1e-6) ctx.reject("prior_look_at", "must differ from prior_eye");
      s.has_prior = true;
      s.prior_eye_T_base = frames::look_at(eye, at, s.up_in_base).inverse();
      s.prior_sigma_m = prior_sigma[0], s.prior_sigma_rad = prior_sigma[1];
    }
    try {
      model_ = robot::load_display_arm(find_config_file(urdf), "flange");
      dev_ = model_->frame("dev");
      tracker_ = std::make_unique<PlateTracker>(PlateMarkers::from_arm(*model_, lamp_radius), s);
    } catch (const std::exception& e) {
      ctx.reject("urdf", e.what());
    }
    if (intrinsics_.size() == 4) camera_.emplace(intrinsics_[0], intrinsics_[1], intrinsics_[2], intrinsics_[3]);
  }

  void tick(Time now) override {
    read_joints(now);
    read_camera_info();
    if (!image_in_.take_latest(frame_)) return;
    if (const std::string bad = image::problem(frame_, {"rgb8", "bgr8", "mono8"}); !bad.empty())
      return reject(image_in_, bad);
    const std::string_view encoding = frame_.encoding().c_str();
    const PixelLayout layout = encoding == "rgb8"   ? PixelLayout::kRgb8
                               : encoding == "bgr8" ? PixelLayout::kBgr8
                                                    : PixelLayout::kMono8;
    const cv::Mat image = image::view(frame_);
    if (!camera_)
      return warn_once("no intrinsics yet: set `intrinsics` or connect camera_info; images are skipped until then");
    const std::int64_t stamp = frame_.header().stamp_ns() ? frame_.header().stamp_ns() : now.ns;
    robot::JointVector q;
    if (!joints_.at(stamp, q))
      return warn_once("no joint state yet: the device's pose is unknown; images are skipped until then");
    const Eigen::Isometry3d base_T_dev = model_->fk(q, dev_);
    const FrameResult& r = tracker_->process(image, layout, stamp, base_T_dev, *camera_);
    if (r.refused != Refusal::kNone) report_refusal(r, stamp);
    publish(r, stamp);
  }

 private:
  // In the diagnostics: logged the first time, counted every time.
  void report_refusal(const FrameResult& r, std::int64_t stamp) {
    char text[256];
    if (r.refused == Refusal::kAmbiguous) {
      std::snprintf(text, sizeof text,
                    "refused a fix at t=%.3f s: its blobs could be more than one set of lamps (kept the prediction)",
                    static_cast<double>(stamp) * 1e-9);
      return warn_once("refused fix: ambiguous lamps", text);
    }
    std::snprintf(text, sizeof text,
                  "refused a fix at t=%.3f s: it would move the camera %.0f mm and turn it %.1f deg in %.2f s "
                  "(max_camera_speed %.2f m/s, max_camera_turn_rate %.2f rad/s)",
                  static_cast<double>(stamp) * 1e-9, r.jump.distance_m * 1e3, r.jump.angle_rad * 180 / M_PI,
                  r.since_trusted_s, tracker_->settings().motion.max_speed, tracker_->settings().motion.max_turn_rate);
    warn_once("refused fix: the camera cannot move that fast", text);
  }

  void read_joints(Time now) {
    robot::JointVector q;
    while (take_checked(joints_in_, joints_msg_)) {
      if (std::string why = msgs::joint_positions(joints_msg_, model_->dof(), q); !why.empty()) {
        reject(joints_in_, why);
        continue;
      }
      joints_.add(joints_msg_.header().stamp_ns() ? joints_msg_.header().stamp_ns() : now.ns, q);
    }
  }

  void read_camera_info() {
    if (!intrinsics_.empty() || !info_in_.take_latest(info_msg_)) return;  // the param wins
    const auto& k = info_msg_.k();
    try {
      camera_.emplace(k[0], k[4], k[2], k[5], std::vector<double>(info_msg_.d().begin(), info_msg_.d().end()));
    } catch (const std::invalid_argument& e) {
      reject(info_in_, std::string(e.what()) + " (the previous intrinsics stay)");
    }
  }

  void publish(const FrameResult& r, std::int64_t stamp) {
    auto& obs = markers_msg_;
    fill_header(obs.header(), stamp, seq_, "eye");
    obs.status(r.state == TrackState::kTracking   ? msg::TRACKING_OK
               : r.state == TrackState::kCoasting ? msg::TRACKING_COASTING
                                                  : msg::TRACKING_LOST);
    obs.acquired(r.acquired);
    obs.blobs(static_cast<std::uint32_t>(r.blobs));
    obs.rejected(static_cast<std::uint32_t>(r.rejected));
    obs.ids().clear(), obs.u().clear(), obs.v().clear();
    for (const auto& m : r.matched) {
      obs.ids().push_back(static_cast<std::uint32_t>(m.id));
      obs.u().push_back(m.u);
      obs.v().push_back(m.v);
    }
    obs.reprojection_rms(r.rms_px);
    obs.frames_without_fix(static_cast<std::uint32_t>(r.frames_without_fix));
    markers_out_.write(obs);
    if (tracker_->has_estimate()) {
      write_pose(eye_T_base_out_, base_cov_out_, "base", tracker_->eye_T_base(), tracker_->eye_T_base_covariance(),
                 stamp);
      write_pose(eye_T_dev_out_, dev_cov_out_, "dev", tracker_->eye_T_dev(), tracker_->eye_T_dev_covariance(), stamp);
    }
    ++seq_;
  }

  void write_pose(Output<msg::PoseStamped>& pose_out, Output<msg::PoseWithCovariance>& cov_out, const char* child,
                  const Eigen::Isometry3d& eye_T_x, const PoseEkf::Matrix6d& cov, std::int64_t stamp) {
    fill_header(pose_msg_.header(), stamp, seq_, "eye");
    pose_msg_.child_frame_id(child);
    msgs::to_msg(eye_T_x, pose_msg_.pose());
    pose_out.write(pose_msg_);
    msgs::to_msg(pose_msg_, cov, cov_msg_);
    cov_out.write(cov_msg_);
  }

  std::vector<double> intrinsics_;
  std::unique_ptr<robot::ArmModel> model_;
  robot::FrameId dev_;
  std::unique_ptr<PlateTracker> tracker_;
  std::optional<CameraModel> camera_;
  JointHistory joints_;
  std::uint64_t seq_ = 0;
  msg::Image frame_;
  msg::CameraInfo info_msg_;
  msg::JointState joints_msg_;
  msg::PoseStamped pose_msg_;
  msg::PoseWithCovariance cov_msg_;
  msg::MarkerObservation markers_msg_;
  Input<msg::Image> image_in_;
  Input<msg::CameraInfo> info_in_;
  Input<msg::JointState> joints_in_;
  Output<msg::PoseStamped> eye_T_base_out_, eye_T_dev_out_;
  Output<msg::PoseWithCovariance> base_cov_out_, dev_cov_out_;
  Output<msg::MarkerObservation> markers_out_;
};

}  // namespace wysiwyf::vision

WYSIWYF_COMPONENT(wysiwyf::vision::MarkerTracker, "marker_tracker")
