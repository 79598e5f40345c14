// The simulated arm on arms other than the PUMA 560, with ideal drives (no drive file): the UR5e
// (6 joints) and the FR3 (7 joints), each at its parked pose of config/pipelines/robots/. The
// arm-side loop (ArmDynamics, JointServo, SafetyGate, SetpointFollower, as arm_sim runs it) and
// arm_sim itself through the Harness: loads, holds still under gravity, follows a 2 cm Cartesian
// setpoint step to within 1 mm and keeps every joint within its limits at every sample. Per-joint
// parameters of another length than the URDF's joint count are refused at their parameter.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arm_interface/arm_ports.hpp"
#include "arm_joint_sim/arm_dynamics.hpp"
#include "arm_joint_sim/joint_servo.hpp"
#include "arm_model/arm_model.hpp"
#include "safety_gate/safety_gate.hpp"
#include "setpoint_following/setpoint_follower.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {
namespace {

using robot::ArmModel;
using robot::JointVector;

constexpr std::int64_t kMs = 1'000'000;
constexpr double kStep = 0.02;  // m, the Cartesian setpoint step along base x

struct ArmCase {
  const char* name;                  // config/robots/<name>.urdf
  std::vector<double> initial_q;     // config/pipelines/robots/<name>-sim.yaml's parked pose
  std::vector<double> acceleration;  // and its acceleration_limits
};

std::ostream& operator<<(std::ostream& out, const ArmCase& arm) { return out << arm.name; }

const ArmCase kUr5e{"ur5e", {2.802180, -1.581828, 1.807510, -0.225596, 1.231347, 1.570657}, {8, 8, 10, 30, 30, 30}};
const ArmCase kFr3{
    "fr3", {0.284092, 0.238745, -0.305931, -2.463769, -0.015183, 4.263556, -1.493028}, {10, 10, 10, 10, 10, 10, 10}};

std::string urdf(const ArmCase& arm) { return std::string(WYSIWYF_CONFIG_DIR) + "/robots/" + arm.name + ".urdf"; }

JointVector vector_of(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::string list(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + std::to_string(v[i]);
  return out + "]";
}

msg::CartesianSetpoint setpoint(std::int64_t stamp_ns, const Eigen::Isometry3d& T) {
  msg::CartesianSetpoint s;
  s.header().stamp_ns(stamp_ns);
  s.header().frame_id("base");
  s.child_frame_id("dev");
  msgs::to_msg(T, s.pose());
  msgs::to_msg(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), s.twist());
  s.source("test");
  return s;
}

// What a run showed: the largest joint excursion while holding, the tip's final error to the
// stepped setpoint, and whether every sample kept every joint within its position limits.
struct Outcome {
  double hold_drift = 0;      // rad, largest |q - q0| before the step
  double hold_dev = 0;        // m, largest dev displacement before the step
  double final_error = 0;     // m, dev to the stepped setpoint at the end
  double worst_margin = 1e9;  // rad, least distance of any joint to its limits (< 0: beyond)
  bool following = false;
};

// The arm-side loop as arm_sim runs it (without the fingertip): 1 s holding at q0, then a
// setpoint kStep further along base x streamed every 20 ms for 2 s.
Outcome run_loop(const ArmCase& c) {
  ArmModel model(urdf(c), "dev");
  const int n = model.dof();
  const robot::DriveParams drive = robot::DriveParams::ideal(n);
  model.set_rotor_inertia(drive.reflected_inertia());
  robot::SafetyConfig config;
  config.limits = model.limits();
  config.max_acceleration = vector_of(c.acceleration);
  robot::SafetyGate gate(config);
  robot::SetpointFollower follower(model, "dev", gate, 10.0, 1e-3);
  const JointVector q0 = vector_of(c.initial_q);
  robot::JointServo servo(model, drive, robot::JointServoConfig{}, q0);
  robot::ArmDynamics arm(model, drive, 1000, 0.01);
  arm.reset(q0);
  const Eigen::Isometry3d start = model.fk(q0);
  Eigen::Isometry3d goal = start;
  goal.translation().x() += kStep;
  const JointVector no_contact = JointVector::Zero(n);
  Outcome out;
  for (int ms = 0; ms < 3000; ++ms) {
    const std::int64_t now = ms * kMs;
    const JointVector q = arm.measured_q(), qd = arm.qd();
    if (ms == 0) gate.reset(q, now);
    gate.check_measured(q, qd);
    if (ms >= 1000 && ms % 20 == 0) follower.take(setpoint(now, goal), now);
    follower.update(now);
    const JointVector ref_q = gate.reference().q, ref_qd = gate.reference().qd;
    const robot::JointReference& ref = gate.step(now);
    const JointVector tau = servo.torque(q, qd, ref_q, ref_qd, ref.qdd);
    for (int s = 0; s < 4; ++s) arm.step(0.25e-3, tau, no_contact);
    if (ms < 1000) {
      out.hold_drift = std::max(out.hold_drift, (arm.q() - q0).cwiseAbs().maxCoeff());
      out.hold_dev = std::max(out.hold_dev, (model.fk(arm.q()).translation() - start.translation()).norm());
    }
    const double margin =
        std::min((arm.q() - config.limits.lower).minCoeff(), (config.limits.upper - arm.q()).minCoeff());
    out.worst_margin = std::min(out.worst_margin, margin);
  }
  out.final_error = (model.fk(arm.q()).translation() - goal.translation()).norm();
  out.following = gate.following();
  return out;
}

class ArmLoop : public ::testing::TestWithParam<ArmCase> {};

TEST_P(ArmLoop, HoldsUnderGravityFollowsACartesianStepAndStaysWithinItsLimits) {
  const Outcome o = run_loop(GetParam());
  std::printf(
      "[measured] %s loop: holding drift %.2e rad (dev %.3f mm), step error %.3f mm, least joint margin %.3f rad\n",
      GetParam().name, o.hold_drift, o.hold_dev * 1e3, o.final_error * 1e3, o.worst_margin);
  EXPECT_LT(o.hold_dev, 1e-4) << "holds still at its parked pose";
  EXPECT_LT(o.final_error, 1e-3) << "follows the 2 cm step to within 1 mm";
  EXPECT_GT(o.worst_margin, 0.0) << "every joint within its limits at every sample";
  EXPECT_TRUE(o.following);
}

INSTANTIATE_TEST_SUITE_P(AnyArm, ArmLoop, ::testing::Values(kUr5e, kFr3),
                         [](const auto& info) { return std::string(info.param.name); });

// arm_sim's parameters for the arm, ideal drives.
std::string params(const ArmCase& c) {
  return std::string("{urdf: robots/") + c.name + ".urdf, drive: '', initial_q: " + list(c.initial_q) +
         ", acceleration_limits: " + list(c.acceleration) + "}";
}

class ArmSimOnArm : public ::testing::TestWithParam<ArmCase> {};

TEST_P(ArmSimOnArm, LoadsHoldsFollowsACartesianStepAndStaysWithinItsLimits) {
  const ArmCase& c = GetParam();
  const int n = static_cast<int>(c.initial_q.size());
  if (!robot::joint_state_carries(n)) {
    // The arm is refused at its URDF, saying what the JointState message carries.
    try {
      Harness h("arm_sim", params(c), 1000);
      ADD_FAILURE() << "an arm the JointState message cannot carry was loaded";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("JointState message carries"), std::string::npos) << e.what();
    }
    GTEST_SKIP() << c.name << ": the JointState message carries " << robot::joint_state_capacity();
  }
  const ArmModel model(urdf(c), "dev");
  Harness h("arm_sim", params(c), 1000);
  auto sp = h.feed<msg::CartesianSetpoint>("setpoint");
  auto js = h.watch<msg::JointState>("joint_state", 4);
  auto dev = h.watch<msg::PoseStamped>("device_pose", 4);
  auto status = h.watch<msg::RobotStatus>("status", 64);
  h.activate();
  const JointVector q0 = vector_of(c.initial_q);
  const Eigen::Isometry3d start = model.fk(q0);
  Eigen::Isometry3d goal = start;
  goal.translation().x() += kStep;
  const robot::ArmLimits& limits = model.limits();
  double hold_dev = 0, worst_margin = 1e9;
  Eigen::Isometry3d last_dev = start;
  msg::RobotStatus last_status;
  for (int ms = 0; ms < 3000; ++ms) {
    const std::int64_t now = ms * kMs;
    if (ms >= 1000 && ms % 20 == 0) sp.write(setpoint(now, goal));
    h.tick(Time{now});
    msg::JointState j;
    msg::PoseStamped d;
    ASSERT_TRUE(js.take(j));
    ASSERT_TRUE(dev.take(d));
    while (status.take(last_status)) {
    }
    JointVector q(n);
    for (int k = 0; k < n; ++k) q[k] = j.position()[static_cast<std::size_t>(k)];
    worst_margin = std::min(worst_margin, std::min((q - limits.lower).minCoeff(), (limits.upper - q).minCoeff()));
    last_dev = msgs::to_isometry(d.pose());
    if (ms < 1000) hold_dev = std::max(hold_dev, (last_dev.translation() - start.translation()).norm());
  }
  const double error = (last_dev.translation() - goal.translation()).norm();
  std::printf("[measured] arm_sim on the %s: holding %.3f mm off, step error %.3f mm, least joint margin %.3f rad\n",
              c.name, hold_dev * 1e3, error * 1e3, worst_margin);
  EXPECT_LT(hold_dev, 1e-4) << "holds still at its parked pose under gravity";
  EXPECT_LT(error, 1e-3) << "follows the 2 cm step to within 1 mm";
  EXPECT_GT(worst_margin, 0.0) << "every joint within its limits at every sample";
  EXPECT_EQ(last_status.state(), msg::ARM_OK) << last_status.reason().c_str();
}

INSTANTIATE_TEST_SUITE_P(AnyArm, ArmSimOnArm, ::testing::Values(kUr5e, kFr3),
                         [](const auto& info) { return std::string(info.param.name); });

// A per-joint list of another length than the URDF's joints is refused at its own parameter,
// with both counts.
void expect_refused(const std::string& p, const std::string& parameter, const std::string& what) {
  try {
    Harness h("arm_sim", p, 1000);
    ADD_FAILURE() << p << " was accepted";
  } catch (const ConfigError& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find("'" + parameter + "'"), std::string::npos) << why;
    EXPECT_NE(why.find(what), std::string::npos) << why;
  }
}

TEST(ArmSimParameters, PerJointListsOfAnotherLengthAreRefusedAtTheirParameter) {
  expect_refused("{acceleration_limits: [8, 8, 10]}", "acceleration_limits", "6 values, got 3");
  expect_refused("{acceleration_limits: [8, 8, 10, 30, 30, 30, 30]}", "acceleration_limits", "6 values, got 7");
  expect_refused("{urdf: robots/ur5e.urdf, drive: '', initial_q: " + list(kUr5e.initial_q) +
                     ", acceleration_limits: [10, 10, 10, 10, 10, 10, 10]}",
                 "acceleration_limits", "6 values, got 7");
  expect_refused("{urdf: robots/ur5e.urdf, drive: '', initial_q: [7, 0, 0, 0, 0, 0]}", "initial_q",
                 "joint 1 (shoulder_pan_joint) at 7.000000 rad is outside its limits");
  expect_refused("{initial_q: [0.1, 0.2]}", "initial_q", "6 values, got 2");
  expect_refused("{servo_kp: [1, 2, 3]}", "servo_kp", "6 values (or none), got 3");
  // The PUMA's drive file names the PUMA's joints, not the UR5e's.
  expect_refused("{urdf: robots/ur5e.urdf, initial_q: " + list(kUr5e.initial_q) + "}", "drive", "joint");
}

}  // namespace
}  // namespace wysiwyf::test
