// setpoint_script: a Cartesian device setpoint stream through timed waypoints, with minimum-jerk
// timing between them (zero velocity and acceleration at each waypoint, continuous velocity), the
// way a test or a demo drives the robot without the haptic loop.
//
// With start_arm (and arm_status, arm_request mapped to the arm's status and request) it starts
// the arm the way the supervisor does: it waits for the arm's status, asks it to clear a fault
// that its input caused (its stream lost while this script's process was away), and starts its
// script once the arm is ready. That is its only start: a fault later (the stream lost again) is
// never cleared by it.
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
    start_arm_ = ctx.param<bool>("start_arm", false,
                                 "start as the display would: wait for arm_status, ask (arm_request) to clear a fault "
                                 "of the arm's input, run the script once the arm is ready");
    arm_status_ =
        ctx.input<msg::RobotStatus>("arm_status", "the arm's RobotStatus (read with start_arm)",
                                    Qos{Reliability::kReliable, Durability::kTransientLocal, 4, 0}.optional_input());
    arm_request_ = ctx.output<msg::ArmRequest>(
        "arm_request", "with start_arm, at its start: asks the arm to clear a fault that its input caused",
        Qos::reliable(8).one_writer());
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
    if (!started_ && !start_arm(now.ns)) return;
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
  // true once the script may run: at once without start_arm; with it, once the arm reports it is
  // following or holding (not faulted), after asking it (every 100 ms) to clear a fault of its input.
  bool start_arm(std::int64_t now_ns) {
    if (!start_arm_) return started_ = true;
    while (arm_status_.take(status_)) have_status_ = true;
    if (!have_status_) {  // (said: an arm_status mapped to nothing would wait silently)
      report_health(Health::kHolding, "start_arm: waiting for the arm's status on input arm_status");
      return false;
    }
    if (status_.state() != msg::ARM_FAULT) {
      if (asked_) log(std::string("the arm is ready (") + status_.reason().c_str() + "): the script starts");
      report_health(Health::kOk);
      return started_ = true;
    }
    if (!status_.clearable()) {
      if (!said_unclearable_)
        report_health(Health::kHolding, std::string("the arm's own fault: ") + status_.reason().c_str());
      said_unclearable_ = true;
      return false;
    }
    if (now_ns - asked_ns_ >= 100'000'000) {
      fill_header(request_.header(), now_ns, request_seq_++, "base");
      request_.request(msg::ARM_CLEAR_INPUT_FAULT);
      request_.reason(("setpoint_script starting after: " + std::string(status_.reason().c_str())).substr(0, 127));
      arm_request_.write(request_);
      if (!asked_)
        log(std::string("the arm holds (") + status_.reason().c_str() + "): asking it to clear that to start");
      asked_ = true, asked_ns_ = now_ns;
    }
    return false;
  }

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
  Input<msg::RobotStatus> arm_status_;
  Output<msg::ArmRequest> arm_request_;
  msg::RobotStatus status_;
  msg::ArmRequest request_;
  bool start_arm_ = false, started_ = false, have_status_ = false, asked_ = false, said_unclearable_ = false;
  std::int64_t asked_ns_ = -1'000'000'000;
  std::uint64_t request_seq_ = 0;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::SetpointScript, "setpoint_script")
