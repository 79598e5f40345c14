#pragma once
// The ports puma_sim and puma_driver share, declared once with one description each: the
// setpoint input, and the joint_state, device_pose and status outputs with the messages of one
// measurement (reused: no allocation per tick).
#include <cstdint>
#include <string>

#include <Eigen/Geometry>

#include "arm_interface/gate_status.hpp"
#include "puma_model/types.hpp"
#include "wysiwyf/context.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot {

class ArmPorts {
 public:
  void declare(Context& ctx);

  Input<msg::CartesianSetpoint> setpoint;

  // joint_state (angles, velocities, motor torques) and device_pose (base_T_tip) of one
  // measurement, with one sequence number.
  void publish_measurement(std::int64_t stamp_ns, std::uint64_t seq, const Vector6d& q, const Vector6d& qd,
                           const Vector6d& effort, const std::string& tip_frame, const Eigen::Isometry3d& base_T_tip);
  // The gate's state on `status` when one is due; true when a fault has just appeared (GateStatus).
  bool publish_status(std::int64_t now_ns, const SafetyGate& gate, const std::string& source) {
    return status_.publish(now_ns, gate, source, status_out_);
  }
  void reset_status() { status_ = GateStatus(); }
  Health health(const SafetyGate& gate) { return status_.health(gate); }

 private:
  Output<msg::JointState> joint_state_out_;
  Output<msg::PoseStamped> device_pose_out_;
  Output<msg::RobotStatus> status_out_;
  GateStatus status_;
  msg::JointState joint_msg_;
  msg::PoseStamped pose_msg_;
};

}  // namespace wysiwyf::robot
