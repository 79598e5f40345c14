#pragma once
// The ports arm_sim and puma_driver share, declared once with one description each: the
// setpoint input, and the joint_state, device_pose and status outputs with the messages of one
// measurement (reused: no allocation per tick).
#include <cstdint>
#include <functional>
#include <string>

#include <Eigen/Geometry>

#include "arm_interface/arm_params.hpp"
#include "arm_interface/gate_status.hpp"
#include "arm_model/arm_types.hpp"
#include "setpoint_following/setpoint_follower.hpp"
#include "wysiwyf/context.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot {

// Whether a JointState message carries the joints of an arm of n joints: its fields hold a fixed
// number of joints (then n must be that number) or are sequences of up to kMaxArmDof.
bool joint_state_carries(int n);
// What a JointState carries, in words ("exactly 6 joints", "1 to 8 joints").
std::string joint_state_capacity();

class ArmPorts {
 public:
  // How the component reports what its inputs brought (its own reject() and log(), which only
  // it may call): a sample it cannot use, on the port it came in on; a line for its log.
  struct Report {
    std::function<void(const Input<msg::CartesianSetpoint>&, const std::string&)> reject_setpoint;
    std::function<void(const Input<msg::ArmRequest>&, const std::string&)> reject_request;
    std::function<void(const std::string&)> log;
  };
  void declare(Context& ctx, Report report);

  Input<msg::CartesianSetpoint> setpoint;
  Input<msg::ArmRequest> request;

  // Every setpoint that came, to the follower (the gate faults on bad ones); one from a source
  // the arm does not take, or one the follower refuses for its stamp, is reported on the
  // setpoint port (counted, logged) and changes nothing.
  void take_setpoints(const ArmParams& params, SetpointFollower& follower, std::int64_t now_ns);
  // Requests to the arm: CLEAR_INPUT_FAULT clears an input fault once the arm stands still; one
  // that cannot be honoured (a fault of the arm, still braking, no fault) is reported.
  void take_requests(SafetyGate& gate, std::int64_t now_ns);
  // At the end of a run: how many servo periods brought a burst of setpoints (none: nothing said).
  void log_bursts(const SafetyGate& gate);

  // joint_state (angles, velocities, motor torques of the n joints: joint_state_carries(n)) and
  // device_pose (base_T_tip) of one measurement, with one sequence number.
  void publish_measurement(std::int64_t stamp_ns, std::uint64_t seq, const JointVector& q, const JointVector& qd,
                           const JointVector& effort, const std::string& tip_frame,
                           const Eigen::Isometry3d& base_T_tip);
  // The gate's state on `status` when one is due; true when a fault has just appeared (GateStatus).
  bool publish_status(std::int64_t now_ns, const SafetyGate& gate, const std::string& source) {
    return status_.publish(now_ns, gate, source, status_out_);
  }
  void reset_status() { status_ = GateStatus(); }
  Health health(const SafetyGate& gate) { return status_.health(gate); }

 private:
  Report report_;
  Output<msg::JointState> joint_state_out_;
  Output<msg::PoseStamped> device_pose_out_;
  Output<msg::RobotStatus> status_out_;
  GateStatus status_;
  msg::JointState joint_msg_;
  msg::PoseStamped pose_msg_;
  msg::CartesianSetpoint setpoint_msg_;
  msg::ArmRequest request_msg_;
  // The process group whose setpoints the arm last took ("" this process): the only one whose
  // requests it takes (a foreign participant cannot clear a fault and take the arm over).
  std::string setpoint_group_;
};

}  // namespace wysiwyf::robot
