// The supervisor alone (the Harness) and the one-writer rule: only the supervisor's setpoints reach
// the robot, and a stale or non-finite input holds it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "display_support.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {

namespace {

constexpr std::int64_t kMs = 1'000'000;

// The supervisor with every input fed as a healthy display would: the plate on the +x face, the
// arm holding until the first setpoint comes, then following, the planner in place, no force but
// the tool's weight.
class SupervisorRig {
 public:
  SupervisorRig()
      : h_("supervisor", "{scene: scenes/display_demo.yaml, recover_after: 0.2}", 1000, &loader_),
        surface_(h_.feed<msg::CartesianSetpoint>("surface")),
        admittance_(h_.feed<msg::CartesianSetpoint>("admittance")),
        wrench_(h_.feed<msg::WrenchStamped>("wrench")),
        device_(h_.feed<msg::PoseStamped>("device_pose")),
        robot_(h_.feed<msg::RobotStatus>("robot_status")),
        planner_(h_.feed<msg::PlannerStatus>("planner_status")),
        out_(h_.watch<msg::CartesianSetpoint>("setpoint")),
        mode_(h_.watch<msg::DisplayMode>("mode")),
        request_(h_.watch<msg::ArmRequest>("arm_request", 64)) {
    plate_.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    plate_.translation() = Eigen::Vector3d(0.7, 0, 0.1);
    h_.activate();
  }

  // One tick at t ms with the surface setpoint at `surface` (NaN allowed), or none.
  void tick(std::int64_t t_ms, const Eigen::Vector3d* surface) {
    const std::int64_t t = t_ms * kMs;
    if (surface) {
      msg::CartesianSetpoint sp;
      fill_header(sp.header(), t, static_cast<std::uint64_t>(t_ms), "base");
      Eigen::Isometry3d T = plate_;
      T.translation() = *surface;
      msgs::to_msg(T, sp.pose());
      sp.source("surface");
      sp.sensed_ns(t - 20 * kMs);  // the hand sample it answers, seen 20 ms ago
      surface_.write(sp);
    }
    if (arm_silent_) return h_.tick(Time{t});  // (nothing from the arm's process)
    msg::WrenchStamped w;  // the tool's weight only: 11.34 N down in base, the sensor's x axis down here
    fill_header(w.header(), t, 0, "ft_sensor");
    const Eigen::Vector3d weight = plate_.linear().transpose() * Eigen::Vector3d(0, 0, -1.1563 * 9.81);
    msgs::to_msg(weight, Eigen::Vector3d::Zero(), w.wrench());
    wrench_.write(w);
    msg::PoseStamped d;
    fill_header(d.header(), t, 0, "base");
    msgs::to_msg(plate_, d.pose());
    device_.write(d);
    msg::RobotStatus r;
    r.state(arm_state_);
    r.clearable(arm_clearable_);
    r.reason(arm_reason_);
    robot_.write(r);
    msg::PlannerStatus p;
    p.state(msg::PLAN_IN_PLACE);
    planner_.write(p);
    h_.tick(Time{t});
    msg::CartesianSetpoint out;
    while (out_.take(out)) {
      sent_.push_back(out);
      if (arm_state_ == msg::ARM_HOLDING) arm_state_ = msg::ARM_OK;  // as the arm: it follows the first one
    }
  }

  msg::DisplayModeKind mode() {
    msg::DisplayMode m;
    while (mode_.take(m)) last_mode_ = m;
    return last_mode_.mode();
  }
  std::string reason() {
    mode();
    return last_mode_.reason().c_str();
  }
  // The newest setpoint written since the last call.
  bool setpoint(msg::CartesianSetpoint& out) {
    if (sent_.empty()) return false;
    out = sent_.back();
    sent_.clear();
    return true;
  }
  // The arm's process silent (killed, frozen): no status, wrist reading or pose from it.
  void silence_arm(bool silent) { arm_silent_ = silent; }
  // The arm's measured plate pose, from the next tick on.
  void move_plate(const Eigen::Vector3d& p) { plate_.translation() = p; }
  Harness& harness() { return h_; }
  // What the arm reports from the next tick on (holding: until a setpoint comes, then following).
  void arm(msg::ArmState state, bool clearable = false, std::string reason = "setpoint rejected: non-finite number") {
    arm_state_ = state, arm_clearable_ = clearable;
    arm_reason_ = state == msg::ARM_FAULT ? std::move(reason) : std::string();
  }
  // The clear requests written since the last call.
  int requests() {
    int n = 0;
    msg::ArmRequest r;
    while (request_.take(r)) n += r.request() == msg::ARM_CLEAR_INPUT_FAULT;
    return n;
  }

 private:
  Loader loader_{Loader({WYSIWYF_COMPONENT_DIR})};
  Harness h_;
  Output<msg::CartesianSetpoint> surface_, admittance_;
  Output<msg::WrenchStamped> wrench_;
  Output<msg::PoseStamped> device_;
  Output<msg::RobotStatus> robot_;
  Output<msg::PlannerStatus> planner_;
  Input<msg::CartesianSetpoint> out_;
  Input<msg::DisplayMode> mode_;
  Input<msg::ArmRequest> request_;
  msg::DisplayMode last_mode_;
  msg::ArmState arm_state_ = msg::ARM_HOLDING;
  bool arm_clearable_ = false, arm_silent_ = false;
  std::vector<msg::CartesianSetpoint> sent_;
  std::string arm_reason_;
  Eigen::Isometry3d plate_ = Eigen::Isometry3d::Identity();
};

}  // namespace

TEST(Supervisor, ANonFiniteSetpointHoldsTheArmWhereItWasSent) {
  SupervisorRig rig;
  const Eigen::Vector3d at(0.7, 0, 0.1), nan(std::nan(""), 0, 0);
  for (int t = 0; t < 50; ++t) rig.tick(t, &at);
  ASSERT_EQ(rig.mode(), msg::MODE_SURFACE);
  rig.tick(50, &nan);
  EXPECT_EQ(rig.mode(), msg::MODE_FAULT);
  EXPECT_NE(rig.reason().find("the surface setpoint: a non-finite"), std::string::npos) << rig.reason();
  EXPECT_EQ(rig.harness().rejected("surface"), 1u);
  msg::CartesianSetpoint held;
  ASSERT_TRUE(rig.setpoint(held));
  EXPECT_NEAR((msgs::to_eigen(held.pose().position()) - at).norm(), 0.0, 1e-12);
  EXPECT_EQ(msgs::to_eigen(held.twist().linear()).norm(), 0.0);
  EXPECT_STREQ(held.source().c_str(), "supervisor/hold");
  EXPECT_EQ(held.sensed_ns(), 0) << "a hold answers no sensor sample";
  // Good input again: back through idle to surface after recover_after, without a step.
  for (int t = 51; t < 400; ++t) rig.tick(t, &at);
  EXPECT_EQ(rig.mode(), msg::MODE_SURFACE) << rig.reason();
  ASSERT_TRUE(rig.setpoint(held));
  EXPECT_STREQ(held.source().c_str(), "supervisor/surface");
  EXPECT_EQ(held.sensed_ns(), (399 - 20) * kMs) << "the planner's sensor stamp, passed on";
}

TEST(Supervisor, AStaleSourceHoldsTheArm) {
  SupervisorRig rig;
  const Eigen::Vector3d at(0.7, 0, 0.1);
  for (int t = 0; t < 50; ++t) rig.tick(t, &at);
  ASSERT_EQ(rig.mode(), msg::MODE_SURFACE);
  for (int t = 50; t < 100; ++t) rig.tick(t, nullptr);  // the planner falls silent
  EXPECT_EQ(rig.mode(), msg::MODE_FAULT);
  EXPECT_NE(rig.reason().find("no surface setpoint for"), std::string::npos) << rig.reason();
  msg::CartesianSetpoint held;
  ASSERT_TRUE(rig.setpoint(held));
  EXPECT_STREQ(held.source().c_str(), "supervisor/hold");
  EXPECT_NEAR((msgs::to_eigen(held.pose().position()) - at).norm(), 0.0, 1e-12);
}

TEST(Supervisor, ASetpointThatJumpsIsAFault) {
  SupervisorRig rig;
  const Eigen::Vector3d at(0.7, 0, 0.1), far(0.7, 0.05, 0.1);
  for (int t = 0; t < 50; ++t) rig.tick(t, &at);
  rig.tick(50, &far);  // 5 cm in 1 ms: 50 m/s
  EXPECT_EQ(rig.mode(), msg::MODE_FAULT);
  EXPECT_NE(rig.reason().find("jumped"), std::string::npos) << rig.reason();
}

// A second writer to the robot's setpoint is a validation error.
TEST(Supervisor, AnArmFaultOfBadInputIsClearedOnceTheInputsAreGoodAndTheDisplayStartsAgain) {
  SupervisorRig rig;
  const Eigen::Vector3d at(0.7, 0, 0.1);
  for (int t = 0; t < 50; ++t) rig.tick(t, &at);
  ASSERT_EQ(rig.mode(), msg::MODE_SURFACE) << rig.reason();
  rig.arm(msg::ARM_FAULT, true);  // e.g. an intruder's NaN reached the arm
  rig.tick(50, &at);
  ASSERT_EQ(rig.mode(), msg::MODE_FAULT);
  EXPECT_NE(rig.reason().find("the arm: setpoint rejected"), std::string::npos) << rig.reason();
  // Every other input good: the request comes after recover_after (0.2 s), then every 100 ms
  // while the arm still reports the fault.
  int first = -1, requests = 0;
  for (int t = 51; t < 600; ++t) {
    rig.tick(t, &at);
    const int n = rig.requests();
    if (n > 0 && first < 0) first = t;
    requests += n;
  }
  EXPECT_GE(first, 50 + 200);
  EXPECT_LE(first, 50 + 202);
  EXPECT_EQ(requests, 1 + (599 - first) / 100);
  EXPECT_EQ(rig.mode(), msg::MODE_FAULT) << "nothing resumes before the arm has cleared";
  // The arm cleared it and holds: the display starts again through idle, as at the start.
  rig.arm(msg::ARM_HOLDING);
  bool idle = false;
  for (int t = 600; t < 1000 && rig.mode() != msg::MODE_SURFACE; ++t) {
    rig.tick(t, &at);
    idle = idle || rig.mode() == msg::MODE_IDLE;
  }
  EXPECT_TRUE(idle);
  EXPECT_EQ(rig.mode(), msg::MODE_SURFACE) << rig.reason();
  EXPECT_EQ(rig.requests(), 0);
}

// A supervisor (re)started while the arm holds after losing its stream sends nothing but the hold
// where the arm stands until it has asked the arm to clear the loss and the arm follows that hold:
// then idle -> surface.
TEST(Supervisor, AnArmThatLostItsStreamIsStartedOnlyThroughTheNormalStart) {
  SupervisorRig rig;
  const Eigen::Vector3d at(0.7, 0, 0.1);
  rig.arm(msg::ARM_FAULT, true, "setpoint stream lost: no setpoint for 31 ms from 'supervisor/surface'");
  int first = -1, requests = 0;
  msg::CartesianSetpoint sp;
  for (int t = 0; t < 400; ++t) {
    rig.tick(t, &at);
    if (rig.setpoint(sp)) {
      EXPECT_STREQ(sp.source().c_str(), "supervisor/hold") << t;
      EXPECT_NEAR((msgs::to_eigen(sp.pose().position()) - at).norm(), 0.0, 1e-12) << "not where the arm stands: " << t;
    }
    const int n = rig.requests();
    if (n > 0 && first < 0) first = t;
    requests += n;
  }
  EXPECT_EQ(rig.mode(), msg::MODE_FAULT);
  EXPECT_NE(rig.reason().find("the arm: setpoint stream lost"), std::string::npos) << rig.reason();
  EXPECT_GE(first, 200);  // recover_after of good input first
  EXPECT_LE(first, 202);
  EXPECT_GE(requests, 2);     // repeated while the arm still reports it
  rig.arm(msg::ARM_HOLDING);  // cleared: holding, waiting for a setpoint near it
  for (int t = 400; t < 800 && rig.mode() != msg::MODE_SURFACE; ++t) rig.tick(t, &at);
  EXPECT_EQ(rig.mode(), msg::MODE_SURFACE) << rig.reason();
  ASSERT_TRUE(rig.setpoint(sp));
  EXPECT_NEAR((msgs::to_eigen(sp.pose().position()) - at).norm(), 0.0, 1e-12) << "from the planner's start";
}

// The arm's process killed mid-run and started again: the new arm stands parked elsewhere and
// waits for its first setpoint. The supervisor's hold goes to where the arm stands, not to where
// it was held (the arm would refuse that jump), and the display starts from there.
TEST(Supervisor, ARestartedArmIsHeldWhereItStandsAndTheDisplayStartsFromThere) {
  SupervisorRig rig;
  const Eigen::Vector3d at(0.7, 0, 0.1), parked(0.5, 0.2, 0.3);
  for (int t = 0; t < 50; ++t) rig.tick(t, &at);
  ASSERT_EQ(rig.mode(), msg::MODE_SURFACE) << rig.reason();
  rig.silence_arm(true);
  msg::CartesianSetpoint sp;
  for (int t = 50; t < 550; ++t) rig.tick(t, &at);
  ASSERT_EQ(rig.mode(), msg::MODE_FAULT);
  EXPECT_NE(rig.reason().find("no wrist reading"), std::string::npos) << rig.reason();
  ASSERT_TRUE(rig.setpoint(sp));
  EXPECT_NEAR((msgs::to_eigen(sp.pose().position()) - at).norm(), 0.0, 1e-12) << "held where it was sent";
  // Nothing from the arm for status_timeout (0.5 s): where it stands is not known, nothing is sent.
  for (int t = 550; t < 1000; ++t) rig.tick(t, &at);
  rig.setpoint(sp);
  for (int t = 1000; t < 1100; ++t) rig.tick(t, &at);
  EXPECT_FALSE(rig.setpoint(sp)) << "a hold sent to an arm silent for longer than status_timeout";
  rig.silence_arm(false);
  rig.arm(msg::ARM_HOLDING);  // the new arm, parked
  rig.move_plate(parked);
  int surface_at = -1;
  for (int t = 1100; t < 2000 && surface_at < 0; ++t) {
    rig.tick(t, &parked);  // (the planner follows what the arm is commanded)
    while (rig.setpoint(sp))
      ASSERT_NEAR((msgs::to_eigen(sp.pose().position()) - parked).norm(), 0.0, 1e-12)
          << "a setpoint away from where the restarted arm stands, at " << t;
    if (rig.mode() == msg::MODE_SURFACE) surface_at = t;
  }
  EXPECT_GE(surface_at, 1100 + 200) << "recover_after of good input first";
  EXPECT_EQ(rig.requests(), 0) << "the new arm had nothing to clear";
}

TEST(Supervisor, AnArmFaultOfTheArmItselfIsNeverAskedToClear) {
  SupervisorRig rig;
  const Eigen::Vector3d at(0.7, 0, 0.1);
  for (int t = 0; t < 50; ++t) rig.tick(t, &at);
  rig.arm(msg::ARM_FAULT, false);  // an overspeed, a force above the limit: the arm's own
  int requests = 0;
  for (int t = 50; t < 2000; ++t) {
    rig.tick(t, &at);
    requests += rig.requests();
  }
  EXPECT_EQ(requests, 0);
  EXPECT_EQ(rig.mode(), msg::MODE_FAULT);
}

TEST(OneWriter, ASecondWriterToTheRobotsSetpointIsRefused) {
  LoopSetup s;
  s.script = {"wait 1"};
  std::string yaml = loop_yaml(s, display_scratch());
  yaml += "  intruder: {type: setpoint_script, rate: 50, topics: {setpoint: robot/setpoint}}\n";
  Loader loader({WYSIWYF_TEST_COMPONENT_DIR, WYSIWYF_COMPONENT_DIR});
  const auto v = validate_pipeline(load_pipeline_from_string(yaml, "two-writers.yaml"), loader);
  ASSERT_FALSE(v.ok());
  std::string all;
  for (const auto& e : v.errors) all += e.str() + "\n";
  EXPECT_NE(all.find("topic 'robot/setpoint': port intruder.setpoint writes it, but supervisor.setpoint"),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("arm.setpoint takes one writer only"), std::string::npos) << all;
}

// Across processes the arm refuses setpoints whose source is not the supervisor's.
TEST(OneWriter, TheArmRefusesAnotherSource) {
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("arm_sim", "{setpoint_source: supervisor}", 1000, &loader);
  auto setpoints = h.feed<msg::CartesianSetpoint>("setpoint");
  auto pose = h.watch<msg::PoseStamped>("device_pose");
  auto status = h.watch<msg::RobotStatus>("status");
  h.activate();
  h.tick(Time{0});
  msg::PoseStamped p;
  ASSERT_TRUE(pose.take_latest(p));
  for (int t = 1; t <= 100; ++t) {
    msg::CartesianSetpoint sp;
    fill_header(sp.header(), t * kMs, static_cast<std::uint64_t>(t), "base");
    sp.child_frame_id("dev");
    sp.pose() = p.pose();
    sp.pose().position().x(sp.pose().position().x() + 0.0001 * t);  // drifting away, were it followed
    sp.source("intruder");
    setpoints.write(sp);
    h.tick(Time{t * kMs});
  }
  EXPECT_EQ(h.rejected("setpoint"), 100u);
  msg::RobotStatus s;
  while (status.take(s)) {
  }
  EXPECT_NE(s.state(), msg::ARM_OK) << "the arm followed a source it should refuse";
  msg::PoseStamped after;
  ASSERT_TRUE(pose.take_latest(after));
  EXPECT_LT((msgs::to_eigen(after.pose().position()) - msgs::to_eigen(p.pose().position())).norm(), 1e-4);
}

}  // namespace wysiwyf::test
