#include "arm_interface/arm_ports.hpp"

#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot {

void ArmPorts::declare(Context& ctx) {
  setpoint = ctx.input<msg::CartesianSetpoint>(
      "setpoint", "base_T_dev and its twist, at any period of 1-20 ms (one writer: a second is a validation error)",
      Qos::reliable(32).one_writer());
  joint_state_out_ =
      ctx.output<msg::JointState>("joint_state", "measured joint angles (encoders), velocities, motor torques");
  device_pose_out_ = ctx.output<msg::PoseStamped>("device_pose", "base_T_dev by FK of the measured joints");
  status_out_ = ctx.output<msg::RobotStatus>(
      "status", "safety state (RobotStatus): ok following a source, holding, or fault, with the reason",
      Qos{Reliability::kReliable, Durability::kTransientLocal, 4, 0});
}

void ArmPorts::publish_measurement(std::int64_t stamp_ns, std::uint64_t seq, const Vector6d& q, const Vector6d& qd,
                                   const Vector6d& effort, const std::string& tip_frame,
                                   const Eigen::Isometry3d& base_T_tip) {
  fill_header(joint_msg_.header(), stamp_ns, seq, "base");
  for (int j = 0; j < kDof; ++j) {
    const auto k = static_cast<std::size_t>(j);
    joint_msg_.position()[k] = q[j];
    joint_msg_.velocity()[k] = qd[j];
    joint_msg_.effort()[k] = effort[j];
  }
  joint_state_out_.write(joint_msg_);
  fill_header(pose_msg_.header(), stamp_ns, seq, "base");
  pose_msg_.child_frame_id(tip_frame);
  msgs::to_msg(base_T_tip, pose_msg_.pose());
  device_pose_out_.write(pose_msg_);
}

}  // namespace wysiwyf::robot
