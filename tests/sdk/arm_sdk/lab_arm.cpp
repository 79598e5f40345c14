// What a lab's out-of-tree arm driver needs from the SDK, used as one would: the installed UR5e's
// URDF with the display's frames, a pose and its inverse kinematics, the safety gate holding the
// arm, a simulated joint servo step, and an RTDE package. Exits 0 and prints "ok" when all hold.
#include <cstdio>
#include <vector>

#include "arm_joint_sim/arm_dynamics.hpp"
#include "arm_joint_sim/joint_servo.hpp"
#include "arm_model/display_frames.hpp"
#include "rtde/packages.hpp"
#include "safety_gate/safety_gate.hpp"

using namespace wysiwyf;

int main() {
  const auto model = robot::load_display_arm(std::string(ROBOTS_DIR) + "/ur5e.urdf", "dev");
  robot::JointVector q(6);
  q << 2.802180, -1.581828, 1.807510, -0.225596, 1.231347, 1.570657;
  const robot::ArmIkResult ik = model->ik_nearest(model->fk(q), q);
  if (!ik.ok() || (ik.q - q).norm() > 1e-9) return std::puts("inverse kinematics"), 1;

  robot::SafetyConfig config;
  config.limits = model->limits();
  config.max_acceleration = robot::JointVector::Constant(6, 8.0);
  robot::SafetyGate gate(config);
  gate.reset(q, 0);
  if ((gate.step(1'000'000).q - q).norm() > 1e-12) return std::puts("the gate moved a holding arm"), 1;

  const robot::DriveParams drive = robot::DriveParams::ideal(6);
  robot::JointServo servo(*model, drive, robot::JointServoConfig{}, q);
  robot::ArmDynamics arm(*model, drive, 0, 0.01);
  arm.reset(q);
  arm.step(1e-3,
           servo.torque(q, robot::JointVector::Zero(6), q, robot::JointVector::Zero(6), robot::JointVector::Zero(6)),
           robot::JointVector::Zero(6));
  if ((arm.q() - q).norm() > 1e-4) return std::puts("the servo let the arm fall"), 1;

  std::vector<std::uint8_t> package;
  robot::rtde::encode_request_protocol_version(package, robot::rtde::kProtocolVersion);
  if (package.size() != 5) return std::puts("RTDE"), 1;
  std::puts("ok");
  return 0;
}
