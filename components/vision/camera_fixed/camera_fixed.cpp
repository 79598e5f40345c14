// camera_fixed: the paper's camera-fixed mode (section 5.1): the camera stands still and its pose
// comes from a calibration file (extrinsics_file.hpp: OpenCV rvec/tvec or a 4x4 matrix) instead
// of the plate tracker: one `type:` line in a pipeline. It publishes what marker_tracker does,
// so its readers do not change: eye_T_base, and eye_T_dev through the arm's forward kinematics
// from the joint state, each also with a covariance (the calibration's stated uncertainty,
// carried to the device for eye_T_dev). With the camera's `camera_info` (one per image) the poses
// are stamped with the newest image's stamp, so they pair with that frame like a tracker's; a
// data-triggered camera_fixed (`trigger: camera_info`) publishes one pair of poses per frame.
#include <memory>

#include "extrinsics_file.hpp"
#include "frames/pose_covariance.hpp"
#include "arm_model/display_frames.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/joint_positions.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision {

class CameraFixed final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("camera-fixed mode: eye_T_base from a calibration file (OpenCV extrinsics), eye_T_dev by kinematics");
    const auto path = ctx.param<std::string>(
        "extrinsics", "",
        "OpenCV FileStorage file with rvec/tvec (solvePnP's), eye_T_base or base_T_eye (cwd, then config/)");
    const auto urdf = ctx.param<std::string>("urdf", "robots/puma560.urdf", "the arm's URDF with the frame dev");
    const double position_sigma =
        ctx.param<double>("position_sigma", 0.001, "the calibration's position uncertainty, m", Range{0, 1});
    const double rotation_sigma =
        ctx.param<double>("rotation_sigma", 0.002, "the calibration's rotation uncertainty, rad", Range{0, 1});
    joints_in_ = ctx.input<msg::JointState>("joint_state", "the arm's joints: where the device is", Qos::sensor(8));
    info_in_ = ctx.input<msg::CameraInfo>(
        "camera_info", "optional: the camera's frames (one a image): the poses take the newest frame's stamp",
        Qos::sensor(4).optional_input());
    eye_T_base_out_ =
        ctx.output<msg::PoseStamped>("eye_T_base", "where the robot base is seen from the camera", Qos::sensor(4));
    eye_T_dev_out_ =
        ctx.output<msg::PoseStamped>("eye_T_dev", "where the device plate is seen from the camera", Qos::sensor(4));
    base_cov_out_ = ctx.output<msg::PoseWithCovariance>("eye_T_base_covariance",
                                                        "eye_T_base with its covariance (eye axes)", Qos::sensor(4));
    dev_cov_out_ = ctx.output<msg::PoseWithCovariance>("eye_T_dev_covariance",
                                                       "eye_T_dev with its covariance (eye axes)", Qos::sensor(4));
    cov_.setZero();
    cov_.topLeftCorner<3, 3>().diagonal().setConstant(position_sigma * position_sigma);
    cov_.bottomRightCorner<3, 3>().diagonal().setConstant(rotation_sigma * rotation_sigma);
    if (path.empty()) return ctx.reject("extrinsics", "expected the camera's calibration file");
    try {
      eye_T_base_ = load_eye_T_base(find_config_file(path));
    } catch (const std::exception& e) {
      ctx.reject("extrinsics", e.what());
    }
    try {
      model_ = robot::load_display_arm(find_config_file(urdf), "flange");
      dev_ = model_->frame("dev");
      q_ = robot::JointVector::Zero(model_->dof());
    } catch (const std::exception& e) {
      ctx.reject("urdf", e.what());
    }
  }

  void tick(Time now) override {
    while (take_checked(joints_in_, joints_msg_)) {
      if (std::string why = msgs::joint_positions(joints_msg_, model_->dof(), q_); !why.empty()) {
        reject(joints_in_, why);
        continue;
      }
      have_joints_ = true;
    }
    // The frame these poses are for: the newest image's, or now without a camera.
    std::int64_t stamp = now.ns;
    if (info_in_.take_latest(info_msg_) && info_msg_.header().stamp_ns() > 0) stamp = info_msg_.header().stamp_ns();
    write(eye_T_base_out_, base_cov_out_, "base", eye_T_base_, cov_, stamp);
    if (have_joints_) {
      const Eigen::Isometry3d base_T_dev = model_->fk(q_, dev_);
      write(eye_T_dev_out_, dev_cov_out_, "dev", eye_T_base_ * base_T_dev,
            frames::compose_covariance(cov_, eye_T_base_, base_T_dev), stamp);
    }
    ++seq_;
  }

 private:
  void write(Output<msg::PoseStamped>& pose_out, Output<msg::PoseWithCovariance>& cov_out, const char* child,
             const Eigen::Isometry3d& eye_T_x, const Eigen::Matrix<double, 6, 6>& cov, std::int64_t stamp) {
    fill_header(pose_msg_.header(), stamp, seq_, "eye");
    pose_msg_.child_frame_id(child);
    msgs::to_msg(eye_T_x, pose_msg_.pose());
    pose_out.write(pose_msg_);
    msgs::to_msg(pose_msg_, cov, cov_msg_);
    cov_out.write(cov_msg_);
  }

  Eigen::Isometry3d eye_T_base_ = Eigen::Isometry3d::Identity();
  Eigen::Matrix<double, 6, 6> cov_;
  std::unique_ptr<robot::ArmModel> model_;
  robot::FrameId dev_{};
  robot::JointVector q_;
  bool have_joints_ = false;
  std::uint64_t seq_ = 0;
  msg::JointState joints_msg_;
  msg::CameraInfo info_msg_;
  Input<msg::CameraInfo> info_in_;
  msg::PoseStamped pose_msg_;
  msg::PoseWithCovariance cov_msg_;
  Input<msg::JointState> joints_in_;
  Output<msg::PoseStamped> eye_T_base_out_, eye_T_dev_out_;
  Output<msg::PoseWithCovariance> base_cov_out_, dev_cov_out_;
};

}  // namespace wysiwyf::vision

WYSIWYF_COMPONENT(wysiwyf::vision::CameraFixed, "camera_fixed")
