// setpoint_script: a Cartesian device setpoint stream through timed waypoints, with minimum-jerk
// timing between them (zero velocity and acceleration at each waypoint, continuous velocity), the
// way a test or a demo drives the robot without the haptic loop.
#include <Eigen/Geometry>

#include "keyframes/keyframes.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::io {

class SetpointScript final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("scripted base_T_dev setpoints through timed waypoints (minimum-jerk between them)");
    const auto waypoints = ctx.param<std::vector<double>>(
        "waypoints", {0, 0.6, 0.0, 0.4, 3.14159265358979, 0, 0},
        "rows of [t s, x y z m, roll pitch yaw rad] (fixed-axis XYZ), times from 0 strictly increasing", std::nullopt,
        Length::rows_of(7, 1));
    loop_ = ctx.param<bool>("loop", false, "start again after the last waypoint");
    frame_id_ = ctx.param<std::string>("frame_id", "base", "parent frame of the setpoint pose");
    child_frame_id_ = ctx.param<std::string>("child_frame_id", "dev", "the frame being placed");
    source_ = ctx.param<std::string>("source", "script", "CartesianSetpoint.source");
    setpoint_ = ctx.output<msg::CartesianSetpoint>("setpoint", "base_T_dev and its twist at each tick (its one writer)",
                                                   Qos::reliable().one_writer());
    pose_ = ctx.output<msg::PoseStamped>("pose", "the same pose as a PoseStamped (e.g. a scripted hand target)");
    try {
      table_ = std::make_unique<Keyframes>(waypoints, 6);
    } catch (const std::invalid_argument& e) {
      ctx.reject("waypoints", e.what());
      return;
    }
    for (int i = 0; i < table_->rows(); ++i) {
      const double* v = table_->values(i);
      positions_.emplace_back(v[0], v[1], v[2]);
      rotations_.push_back(Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                           Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                           Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()));
    }
  }

  void tick(Time now) override {
    const Keyframes::Segment seg = table_->at(time_.at(now.ns, table_->end_time(), loop_));
    const double tau = seg.tau, tau2 = tau * tau;
    const double s = tau2 * tau * (10 - 15 * tau + 6 * tau2);                                  // min-jerk
    const double ds = seg.duration > 0 ? 30 * tau2 * (1 - 2 * tau + tau2) / seg.duration : 0;  // d s / d t
    const Eigen::Vector3d p = positions_[seg.from] + s * (positions_[seg.to] - positions_[seg.from]);
    const Eigen::Quaterniond q = rotations_[seg.from].slerp(s, rotations_[seg.to]);
    const Eigen::Vector3d v = ds * (positions_[seg.to] - positions_[seg.from]);
    // The slerp rotates about one fixed axis (in the base frame) at rate ds * angle.
    const Eigen::AngleAxisd step(rotations_[seg.to] * rotations_[seg.from].inverse());
    const Eigen::Vector3d w = ds * step.angle() * step.axis();

    fill_header(msg_.header(), now.ns, seq_++, frame_id_.c_str());
    msg_.child_frame_id(child_frame_id_);
    msgs::to_msg(p, q, msg_.pose());
    msgs::to_msg(v, w, msg_.twist());
    msg_.source(source_);
    setpoint_.write(msg_);
    pose_msg_.header() = msg_.header();
    pose_msg_.child_frame_id(child_frame_id_);
    pose_msg_.pose() = msg_.pose();
    pose_.write(pose_msg_);
  }

 private:
  std::unique_ptr<Keyframes> table_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Quaterniond> rotations_;
  bool loop_ = false;
  std::string frame_id_, child_frame_id_, source_;
  ScriptTime time_;
  std::uint64_t seq_ = 0;
  msg::CartesianSetpoint msg_;
  msg::PoseStamped pose_msg_;
  Output<msg::CartesianSetpoint> setpoint_;
  Output<msg::PoseStamped> pose_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::SetpointScript, "setpoint_script")
