// The safety gate (libs/robot/safety_gate) on its own: every guarantee of safety_gate.hpp on
// synthetic targets, stepped on simulated time (no clock).
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "arm_model/arm_model.hpp"
#include "safety_gate/safety_gate.hpp"

namespace wysiwyf::robot {
namespace {

const std::string kUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf";
constexpr std::int64_t kMs = 1'000'000;
constexpr double kDt = 1e-3;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ArmIkResult ik_ok(const Vector6d& q) {
  ArmIkResult r;
  r.status = ArmIkStatus::kOk;
  r.q = q;
  r.branch = 0;
  return r;
}

SetpointInput setpoint_at(const Eigen::Isometry3d& pose) {
  SetpointInput in;
  in.position = pose.translation();
  const Eigen::Quaterniond q(pose.linear());
  in.quaternion_xyzw = Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
  return in;
}

class SafetyGateTest : public ::testing::Test {
 protected:
  ArmModel model{kUrdf, "dev"};
  SafetyConfig config = make_config();
  Vector6d q0 = (Vector6d() << 0.2555, -0.1524, -2.5936, 0.2758, 1.1887, -0.1052).finished();
  std::int64_t now = 0;

  SafetyConfig make_config() {
    SafetyConfig c;
    c.limits = model.limits();
    c.max_acceleration = (Vector6d() << 8, 8, 10, 30, 30, 30).finished();
    c.dt = kDt;
    c.max_joint_target_step = 100;  // these tests jump targets on purpose (IK branch changes: own test)
    return c;
  }

  // Every step of the reference must respect these; counts the steps checked.
  struct Checker {
    const SafetyGate& gate;
    Vector6d q_prev, v_prev;
    double worst_velocity = 0, worst_acceleration = 0;  // as a share of the reference's limits
    int steps = 0;
    explicit Checker(const SafetyGate& g) : gate(g), q_prev(g.reference().q), v_prev(g.reference().qd) {}
    void check(const JointReference& r) {
      const Vector6d lo = gate.reference_lower(), hi = gate.reference_upper();
      for (int j = 0; j < kDof; ++j) {
        ASSERT_GE(r.q[j], std::min(lo[j], q_prev[j])) << "joint " << j + 1 << " step " << steps;
        ASSERT_LE(r.q[j], std::max(hi[j], q_prev[j])) << "joint " << j + 1 << " step " << steps;
        ASSERT_GE(r.q[j], gate.config().limits.lower[j]);
        ASSERT_LE(r.q[j], gate.config().limits.upper[j]);
        const double v = (r.q[j] - q_prev[j]) / kDt, a = (r.qd[j] - v_prev[j]) / kDt;
        EXPECT_NEAR(v, r.qd[j], 1e-9);  // the reference is consistent: position integrates velocity
        worst_velocity = std::max(worst_velocity, std::abs(v) / gate.reference_velocity_limit()[j]);
        worst_acceleration = std::max(worst_acceleration, std::abs(a) / gate.reference_acceleration_limit()[j]);
      }
      q_prev = r.q;
      v_prev = r.qd;
      ++steps;
    }
  };

  void start(SafetyGate& gate, const Vector6d& q) {
    now = 0;
    gate.reset(q, now);
  }
  // One servo period while streaming setpoints at `pose` every `period_ms`.
  const JointReference& follow(SafetyGate& gate, const Vector6d& target, int period_ms = 1,
                               const Vector6d& qd = Vector6d::Zero()) {
    now += kMs;
    if ((now / kMs) % period_ms == 0) {
      Eigen::Isometry3d accepted;
      gate.accept_setpoint(now, setpoint_at(model.fk(gate.reference().q)), model.fk(gate.reference().q), accepted);
    }
    gate.set_joint_target(ik_ok(target), qd);
    return gate.step(now);
  }
};

TEST_F(SafetyGateTest, DoesNothingBeforeReset) {
  SafetyGate gate(config);
  EXPECT_EQ(gate.state(), SafetyState::kFault);
  Eigen::Isometry3d pose;
  EXPECT_FALSE(gate.accept_setpoint(0, setpoint_at(model.fk(q0)), model.fk(q0), pose));
  const JointReference& r = gate.step(kMs);
  EXPECT_EQ(r.qd.norm(), 0.0);
}

TEST_F(SafetyGateTest, LargeStepUsesFullVelocityAndAccelerationButNeverMoreAndStopsWithoutOvershoot) {
  SafetyGate gate(config);
  start(gate, q0);
  const Vector6d target = q0 + (Vector6d() << 1.5, -0.6, 1.2, 1.5, -1.0, 2.0).finished();
  Checker check(gate);
  Vector6d peak_v = Vector6d::Zero();
  Vector6d overshoot = Vector6d::Zero();
  for (int i = 0; i < 3000; ++i) {
    const JointReference& r = follow(gate, target);
    check.check(r);
    peak_v = peak_v.cwiseMax(r.qd.cwiseAbs());
    for (int j = 0; j < kDof; ++j)
      overshoot[j] = std::max(overshoot[j], (r.q[j] - target[j]) * (target[j] > q0[j] ? 1.0 : -1.0));
  }
  EXPECT_EQ(gate.state(), SafetyState::kOk) << gate.reason();
  EXPECT_LE(check.worst_velocity, 1.0 + 1e-12);
  EXPECT_LE(check.worst_acceleration, 1.0 + 1e-9);
  // Joints 1, 4 and 6 move far enough to reach their reference velocity limit.
  for (int j : {0, 3, 5}) EXPECT_NEAR(peak_v[j], gate.reference_velocity_limit()[j], 1e-9) << "joint " << j + 1;
  EXPECT_LT(overshoot.maxCoeff(), 1e-9);
  EXPECT_LT((gate.reference().q - target).cwiseAbs().maxCoeff(), 1e-6);  // settled after 3 s
  EXPECT_LT(gate.reference().qd.cwiseAbs().maxCoeff(), 1e-4);
}

TEST_F(SafetyGateTest, TargetBeyondAPositionLimitStopsAtTheMarginEvenAtFullSpeed) {
  SafetyGate gate(config);
  Vector6d start_q = q0;
  start_q[4] = 0.0;
  start(gate, start_q);
  Vector6d target = start_q;
  target[4] = 5.0;   // far beyond +100 deg
  target[0] = -9.0;  // far beyond -160 deg
  Checker check(gate);
  for (int i = 0; i < 4000; ++i) check.check(follow(gate, target, 1, Vector6d::Constant(3.0)));
  EXPECT_LE(check.worst_velocity, 1.0 + 1e-12);
  EXPECT_LE(check.worst_acceleration, 1.0 + 1e-9);
  EXPECT_NEAR(gate.reference().q[4], gate.reference_upper()[4], 1e-6);
  EXPECT_NEAR(gate.reference().q[0], gate.reference_lower()[0], 1e-6);
  EXPECT_LE(gate.reference().q[4], config.limits.upper[4] - config.position_margin);
}

TEST_F(SafetyGateTest, RandomTargetsNeverBreakAnyLimit) {
  // Fuzz: targets anywhere (also far outside the limits), jumping every few ms, with random
  // feedforward velocities; checked at every step.
  SafetyGate gate(config);
  start(gate, q0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Checker check(gate);
  Vector6d target = q0, qd = Vector6d::Zero();
  // Keep each target jump below max_joint_target_step so the gate keeps following.
  for (int i = 0; i < 20000; ++i) {
    if (i % 7 == 0) {
      for (int j = 0; j < kDof; ++j) {
        target[j] = std::clamp(target[j] + 0.19 * u(rng), -7.0, 7.0);
        qd[j] = 10.0 * u(rng);
      }
    }
    check.check(follow(gate, target, 1, qd));
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_EQ(gate.state(), SafetyState::kOk) << gate.reason();
  EXPECT_LE(check.worst_velocity, 1.0 + 1e-12);
  EXPECT_LE(check.worst_acceleration, 1.0 + 1e-9);
  EXPECT_GT(check.worst_velocity, 0.99);  // the fuzz did push against the limits
  EXPECT_GT(check.worst_acceleration, 0.99);
}

TEST_F(SafetyGateTest, WatchdogBrakesWithinTheBrakingBoundAndHoldsThenResumes) {
  SafetyGate gate(config);
  start(gate, q0);
  Vector6d target = q0;
  // Cruise: joint 4 at full reference speed.
  for (int i = 0; i < 800; ++i) {
    target[3] = q0[3] + 0.0026 * i;  // 2.6 rad/s > the reference limit: saturates
    follow(gate, target, 20, Vector6d::Unit(3) * 2.6);
  }
  ASSERT_EQ(gate.state(), SafetyState::kOk);
  const double v0 = gate.reference().qd[3];
  ASSERT_NEAR(std::abs(v0), gate.reference_velocity_limit()[3], 1e-9);
  // The stream stops: no setpoint, no new joint target.
  const std::int64_t last_setpoint = now - (now / kMs) % 20 * kMs;
  Checker check(gate);
  int stopped_at = -1;
  for (int i = 1; i <= 1500; ++i) {
    now += kMs;
    check.check(gate.step(now));
    const std::int64_t timeout_ns = static_cast<std::int64_t>(config.setpoint_timeout * 1e9);  // (in ns, as the gate)
    EXPECT_EQ(gate.state(), now - last_setpoint <= timeout_ns ? SafetyState::kOk : SafetyState::kFault) << i;
    if (stopped_at < 0 && gate.reference().qd.norm() == 0.0) stopped_at = i;
  }
  EXPECT_LE(check.worst_velocity, 1.0 + 1e-12);
  EXPECT_LE(check.worst_acceleration, 1.0 + 1e-9);
  EXPECT_NE(gate.reason().find("no setpoint"), std::string::npos) << gate.reason();
  // Timeout, then braking at the reference acceleration limit: v0 / a + one period.
  const double bound_ms =
      config.setpoint_timeout * 1e3 + 20 + std::abs(v0) / gate.reference_acceleration_limit()[3] * 1e3 + 1;
  ASSERT_GT(stopped_at, 0);
  EXPECT_LE(stopped_at, bound_ms);
  // The loss is an input fault: a fresh setpoint near where the arm stopped is not followed by
  // itself, only once the display has asked to resume (cleared it).
  EXPECT_TRUE(gate.input_fault());
  Eigen::Isometry3d pose;
  EXPECT_FALSE(
      gate.accept_setpoint(now, setpoint_at(model.fk(gate.reference().q)), model.fk(gate.reference().q), pose));
  EXPECT_EQ(gate.state(), SafetyState::kFault);
  ASSERT_TRUE(gate.clear_input_fault(now));
  EXPECT_EQ(gate.state(), SafetyState::kHolding);
  ASSERT_TRUE(gate.accept_setpoint(now, setpoint_at(model.fk(gate.reference().q)), model.fk(gate.reference().q), pose));
  EXPECT_EQ(gate.state(), SafetyState::kOk);
}

TEST_F(SafetyGateTest, TheStreamIsLostAfterThreeOfItsOwnPeriodsAtMostTheTimeout) {
  for (const int period_ms : {1, 7, 20, 30}) {
    SafetyGate gate(config);
    start(gate, q0);
    EXPECT_EQ(gate.setpoint_loss_timeout_ns(), 60 * kMs) << "the timeout while the period is unknown";
    for (int i = 0; i < 300; ++i) follow(gate, q0, period_ms);
    ASSERT_EQ(gate.state(), SafetyState::kOk);
    EXPECT_EQ(gate.setpoint_period_ns(), period_ms * kMs);
    const std::int64_t expected = std::min<std::int64_t>(3 * period_ms, 60) * kMs;
    EXPECT_EQ(gate.setpoint_loss_timeout_ns(), expected) << period_ms;
    const std::int64_t last_setpoint = now - (now / kMs) % period_ms * kMs;
    while (gate.state() == SafetyState::kOk) {
      now += kMs;
      gate.step(now);
    }
    EXPECT_EQ(now - last_setpoint, expected + kMs) << period_ms << " ms stream: held one tick after the timeout";
    EXPECT_NE(gate.reason().find("lost after"), std::string::npos) << gate.reason();
    // Resumed (asked to), the stream's period is learned anew.
    ASSERT_TRUE(gate.clear_input_fault(now)) << gate.reason();
    Eigen::Isometry3d pose;
    ASSERT_TRUE(
        gate.accept_setpoint(now, setpoint_at(model.fk(gate.reference().q)), model.fk(gate.reference().q), pose));
    EXPECT_EQ(gate.setpoint_period_ns(), 0);
  }
}

// A stream from another process: its loss names the process (the lost group), beside the source.
TEST_F(SafetyGateTest, ALostStreamFromAnotherProcessNamesIt) {
  SafetyGate gate(config);
  start(gate, q0);
  Eigen::Isometry3d pose;
  for (int i = 0; i < 20; ++i) {
    now += kMs;
    SetpointInput in = setpoint_at(model.fk(q0));
    in.source = "supervisor/surface";
    in.writer = "demo-hosts/display/4711";
    in.stamp_ns = now;
    ASSERT_TRUE(gate.accept_setpoint(now, in, model.fk(q0), pose)) << gate.reason();
    gate.set_joint_target(ik_ok(q0), Vector6d::Zero());
    gate.step(now);
  }
  while (gate.state() == SafetyState::kOk) gate.step(now += kMs);
  EXPECT_NE(gate.reason().find("no setpoint for 4 ms from 'supervisor/surface' in process 'demo-hosts/display/4711' "
                               "(its stream came every 1 ms; lost after 3 ms)"),
            std::string::npos)
      << gate.reason();
}

// A 100 Hz stream whose first samples reach the arm together (queued while DDS matched the two
// processes, then delivered one per servo period): learned from the arrivals its period would
// read as 1 ms and its first ordinary 10 ms gap as a loss; learned from the sender's stamps it is
// 10 ms, and no period is trusted before kMinIntervals of them.
TEST_F(SafetyGateTest, TheStreamsPeriodComesFromItsStampsSoADeliveryBurstIsNotALoss) {
  for (const bool stamped : {true, false}) {
    SafetyGate gate(config);
    start(gate, q0);
    const Eigen::Isometry3d pose = model.fk(q0);
    Eigen::Isometry3d accepted;
    const auto deliver = [&](std::int64_t stamp_ms) {
      SetpointInput in = setpoint_at(pose);
      in.stamp_ns = stamped ? stamp_ms * kMs : -1;
      EXPECT_TRUE(gate.accept_setpoint(now, in, pose, accepted)) << gate.reason();
    };
    const auto tick_to = [&](std::int64_t t_ms) {
      while (now < t_ms * kMs) {
        now += kMs;
        gate.set_joint_target(ik_ok(q0), Vector6d::Zero());
        gate.step(now);
      }
    };
    for (std::int64_t k = 0; k < 6; ++k) tick_to(100 + k), deliver(10 * k);  // stamps 0 .. 50, at 100 .. 105 ms
    tick_to(114);  // the next, stamped 60 ms, comes at 115 ms: 10 ms after the last arrival
    if (stamped) {
      EXPECT_EQ(gate.setpoint_period_ns(), 10 * kMs);
      EXPECT_EQ(gate.state(), SafetyState::kOk) << gate.reason();
      tick_to(115), deliver(60);
      for (std::int64_t k = 7; k < 30; ++k) tick_to(55 + 10 * k), deliver(10 * k);  // on time from then on
      EXPECT_EQ(gate.state(), SafetyState::kOk) << gate.reason();
    } else {
      EXPECT_EQ(gate.setpoint_period_ns(), kMs);
      EXPECT_EQ(gate.state(), SafetyState::kFault) << "unstamped, the burst reads as a 1 kHz stream, lost";
    }
  }
}

// Rate bursts: several setpoints in one servo period (a sender writing faster than its stream, a
// network's bunching) are counted, and each is screened against the setpoint before the period:
// 4 cm steps, each within max_setpoint_step (10 cm) of the one before, add up to 12 cm by the
// third within one period, a jump; the same steps one per period are followed.
TEST_F(SafetyGateTest, ABurstOfSmallStepsInOneServoPeriodIsScreenedAsOneJumpAndCounted) {
  const Eigen::Isometry3d start_pose = model.fk(q0);
  const auto step_to = [&](int k) {
    Eigen::Isometry3d T = start_pose;
    T.translation().x() += 0.04 * k;
    SetpointInput in = setpoint_at(T);
    in.stamp_ns = now;
    return in;
  };
  const auto servo_period = [&](SafetyGate& gate) {
    now += kMs;
    gate.set_joint_target(ik_ok(q0), Vector6d::Zero());
    gate.step(now);
  };
  Eigen::Isometry3d accepted;
  {  // one per servo period: followed
    SafetyGate gate(config);
    start(gate, q0);
    for (int k = 0; k <= 4; ++k) {
      EXPECT_TRUE(gate.accept_setpoint(now, step_to(k), start_pose, accepted)) << k << ": " << gate.reason();
      servo_period(gate);
    }
    EXPECT_EQ(gate.burst_periods(), 0u);
  }
  {  // the first at the arm, then a period with two (counted), then four in one: a jump
    SafetyGate gate(config);
    start(gate, q0);
    ASSERT_TRUE(gate.accept_setpoint(now, step_to(0), start_pose, accepted)) << gate.reason();
    servo_period(gate);
    ASSERT_TRUE(gate.accept_setpoint(now, step_to(0), start_pose, accepted)) << gate.reason();
    ASSERT_TRUE(gate.accept_setpoint(now, step_to(1), start_pose, accepted)) << gate.reason();
    servo_period(gate);
    EXPECT_EQ(gate.burst_periods(), 1u);
    EXPECT_EQ(gate.largest_burst(), 2);
    for (int k = 2; k <= 4; ++k) {
      const bool ok = gate.accept_setpoint(now, step_to(k), start_pose, accepted);
      EXPECT_EQ(ok, k < 4) << k << ": " << gate.reason();  // 4, 8, then 12 cm from the period's start
    }
    EXPECT_TRUE(gate.input_fault());
    EXPECT_NE(gate.reason().find("0.1200 m from the setpoint before this servo period (3 setpoints in it)"),
              std::string::npos)
        << gate.reason();
  }
  {  // a burst as the first setpoints: each against the arm's position
    SafetyGate gate(config);
    start(gate, q0);
    for (int k = 0; k <= 3; ++k) {
      const bool ok = gate.accept_setpoint(now, step_to(k), start_pose, accepted);
      EXPECT_EQ(ok, k < 3) << k << ": " << gate.reason();
    }
    EXPECT_NE(gate.reason().find("from the arm's position (4 setpoints in this servo period)"), std::string::npos)
        << gate.reason();
  }
}

TEST_F(SafetyGateTest, AnInputFaultClearsAtAStandstillAndAnArmFaultDoesNot) {
  SafetyGate gate(config);
  start(gate, q0);
  Vector6d target = q0;
  for (int i = 0; i < 300; ++i) {
    target[0] = q0[0] + 0.001 * i;
    follow(gate, target, 1, Vector6d::Unit(0));
  }
  SetpointInput bad = setpoint_at(model.fk(q0));
  bad.position.x() = kNaN;
  Eigen::Isometry3d pose;
  EXPECT_FALSE(gate.accept_setpoint(now, bad, model.fk(q0), pose));
  ASSERT_TRUE(gate.input_fault());
  EXPECT_FALSE(gate.clear_input_fault(now)) << "still braking";
  while (gate.reference().qd.cwiseAbs().maxCoeff() > 0) gate.step(now += kMs);
  EXPECT_TRUE(gate.clear_input_fault(now));
  EXPECT_EQ(gate.state(), SafetyState::kHolding);
  EXPECT_FALSE(gate.clear_input_fault(now)) << "nothing left to clear";
  follow(gate, gate.reference().q);
  EXPECT_EQ(gate.state(), SafetyState::kOk);
  // The arm's own fault stays.
  gate.check_wrench(Eigen::Vector3d(0, 0, 500), Eigen::Vector3d::Zero());
  ASSERT_EQ(gate.state(), SafetyState::kFault);
  EXPECT_FALSE(gate.input_fault());
  while (gate.reference().qd.cwiseAbs().maxCoeff() > 0) gate.step(now += kMs);
  EXPECT_FALSE(gate.clear_input_fault(now));
  EXPECT_EQ(gate.state(), SafetyState::kFault);
}

TEST_F(SafetyGateTest, NonFiniteSetpointFaultsLatchesAndHoldsUntilReset) {
  SafetyGate gate(config);
  start(gate, q0);
  for (int i = 0; i < 100; ++i) follow(gate, q0);
  ASSERT_EQ(gate.state(), SafetyState::kOk);
  for (const char* field : {"position", "quaternion", "twist"}) {
    SafetyGate g(config);
    g.reset(q0, now);
    SetpointInput bad = setpoint_at(model.fk(q0));
    if (std::string(field) == "position") bad.position.y() = kNaN;
    if (std::string(field) == "quaternion") bad.quaternion_xyzw[3] = std::numeric_limits<double>::infinity();
    if (std::string(field) == "twist") bad.angular_velocity.z() = kNaN;
    Eigen::Isometry3d pose;
    EXPECT_FALSE(g.accept_setpoint(now, bad, model.fk(q0), pose)) << field;
    EXPECT_EQ(g.state(), SafetyState::kFault) << field;
    EXPECT_NE(g.reason().find("non-finite"), std::string::npos) << g.reason();
  }
  // On the running gate: NaN, then good setpoints and targets; nothing moves.
  SetpointInput bad = setpoint_at(model.fk(q0));
  bad.position.x() = kNaN;
  Eigen::Isometry3d pose;
  EXPECT_FALSE(gate.accept_setpoint(now, bad, model.fk(q0), pose));
  ASSERT_EQ(gate.state(), SafetyState::kFault);
  const std::string reason = gate.reason();
  const Vector6d held = gate.reference().q;
  Vector6d away = q0;
  away[0] += 0.1;
  for (int i = 0; i < 500; ++i) {
    const JointReference& r = follow(gate, away);  // good input after the fault
    EXPECT_EQ(r.q, held);
    EXPECT_EQ(r.qd.norm(), 0.0);
  }
  EXPECT_EQ(gate.state(), SafetyState::kFault);
  EXPECT_EQ(gate.reason(), reason);  // the first reason stays
  gate.reset(held, now);
  EXPECT_EQ(gate.state(), SafetyState::kHolding);
  follow(gate, held);
  EXPECT_EQ(gate.state(), SafetyState::kOk);
}

TEST_F(SafetyGateTest, MalformedSetpointsFaultWithTheirReason) {
  struct Case {
    const char* expect;
    void (*spoil)(SetpointInput&);
  };
  const Case cases[] = {
      {"quaternion norm", [](SetpointInput& s) { s.quaternion_xyzw = Eigen::Vector4d::Zero(); }},
      {"quaternion norm", [](SetpointInput& s) { s.quaternion_xyzw *= 1.1; }},
      {"linear speed", [](SetpointInput& s) { s.linear_velocity.x() = 3.0; }},
      {"angular speed", [](SetpointInput& s) { s.angular_velocity.y() = -7.0; }},
      {"m from the arm", [](SetpointInput& s) { s.position.z() += 0.15; }},
      {"turned",
       [](SetpointInput& s) {
         const Eigen::Quaterniond q(s.quaternion_xyzw[3], s.quaternion_xyzw[0], s.quaternion_xyzw[1],
                                    s.quaternion_xyzw[2]);
         const Eigen::Quaterniond r = Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()) * q;
         s.quaternion_xyzw = Eigen::Vector4d(r.x(), r.y(), r.z(), r.w());
       }},
  };
  for (const Case& c : cases) {
    SafetyGate gate(config);
    gate.reset(q0, 0);
    SetpointInput sp = setpoint_at(model.fk(q0));
    c.spoil(sp);
    Eigen::Isometry3d pose;
    EXPECT_FALSE(gate.accept_setpoint(kMs, sp, model.fk(q0), pose)) << c.expect;
    EXPECT_EQ(gate.state(), SafetyState::kFault) << c.expect;
    EXPECT_NE(gate.reason().find(c.expect), std::string::npos) << gate.reason();
  }
  // A jump between consecutive setpoints of a running stream (one per servo period).
  SafetyGate gate(config);
  gate.reset(q0, 0);
  Eigen::Isometry3d pose;
  ASSERT_TRUE(gate.accept_setpoint(kMs, setpoint_at(model.fk(q0)), model.fk(q0), pose));
  gate.step(kMs);
  Eigen::Isometry3d far = model.fk(q0);
  far.translation().x() += 0.09;  // fine once
  ASSERT_TRUE(gate.accept_setpoint(2 * kMs, setpoint_at(far), model.fk(q0), pose));
  gate.step(2 * kMs);
  far.translation().x() += 0.11;  // too far from the previous setpoint
  EXPECT_FALSE(gate.accept_setpoint(3 * kMs, setpoint_at(far), model.fk(q0), pose));
  EXPECT_NE(gate.reason().find("previous setpoint"), std::string::npos) << gate.reason();
}

TEST_F(SafetyGateTest, UnreachableOrJumpingIkTargetsFault) {
  for (ArmIkStatus status :
       {ArmIkStatus::kOutOfReach, ArmIkStatus::kNotFound, ArmIkStatus::kJointLimits, ArmIkStatus::kInvalidInput}) {
    SafetyGate gate(config);
    start(gate, q0);
    follow(gate, q0);
    ASSERT_EQ(gate.state(), SafetyState::kOk);
    ArmIkResult ik;
    ik.status = status;
    gate.set_joint_target(ik, Vector6d::Zero());
    EXPECT_EQ(gate.state(), SafetyState::kFault);
    EXPECT_NE(gate.reason().find(to_string(status)), std::string::npos) << gate.reason();
    const Vector6d held = gate.reference().q;
    for (int i = 0; i < 50; ++i) EXPECT_EQ(gate.step(now += kMs).q, held);
  }
  SafetyConfig strict = config;
  strict.max_joint_target_step = 0.2;
  SafetyGate gate(strict);
  start(gate, q0);
  follow(gate, q0);
  Vector6d flipped = q0;
  flipped[3] += 3.14159;  // the wrist-flip solution
  gate.set_joint_target(ik_ok(flipped), Vector6d::Zero());
  EXPECT_EQ(gate.state(), SafetyState::kFault);
  EXPECT_NE(gate.reason().find("IK branch"), std::string::npos) << gate.reason();
}

TEST_F(SafetyGateTest, ForceLimitNonFiniteWrenchFollowingErrorAndOverspeedFault) {
  auto running = [&](SafetyGate& gate) {
    start(gate, q0);
    follow(gate, q0);
    ASSERT_EQ(gate.state(), SafetyState::kOk);
  };
  {
    SafetyGate gate(config);
    running(gate);
    gate.check_wrench(Eigen::Vector3d(0, 0, 99.0), Eigen::Vector3d::Zero());
    EXPECT_EQ(gate.state(), SafetyState::kOk);
    gate.check_wrench(Eigen::Vector3d(60, 0, -85.0), Eigen::Vector3d::Zero());
    EXPECT_EQ(gate.state(), SafetyState::kFault);
    EXPECT_NE(gate.reason().find("measured force"), std::string::npos) << gate.reason();
  }
  {
    SafetyGate gate(config);
    running(gate);
    gate.check_wrench(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 11.0, 0));
    EXPECT_NE(gate.reason().find("measured torque"), std::string::npos) << gate.reason();
  }
  {
    SafetyGate gate(config);
    running(gate);
    gate.check_wrench(Eigen::Vector3d(kNaN, 0, 0), Eigen::Vector3d::Zero());
    EXPECT_NE(gate.reason().find("non-finite force"), std::string::npos) << gate.reason();
  }
  {
    SafetyGate gate(config);
    running(gate);
    Vector6d q = gate.reference().q;
    q[1] += 0.09;
    gate.check_measured(q, Vector6d::Zero());
    EXPECT_EQ(gate.state(), SafetyState::kOk);
    q[1] += 0.02;
    gate.check_measured(q, Vector6d::Zero());
    EXPECT_NE(gate.reason().find("joint 2 following error"), std::string::npos) << gate.reason();
  }
  {
    SafetyGate gate(config);
    running(gate);
    gate.check_measured(gate.reference().q, Vector6d::Unit(2) * -3.8);
    EXPECT_NE(gate.reason().find("joint 3 overspeed"), std::string::npos) << gate.reason();
  }
  {
    SafetyGate gate(config);
    Vector6d beyond = q0;
    beyond[4] = 1.8;  // beyond +100 deg
    gate.reset(beyond, 0);
    EXPECT_EQ(gate.state(), SafetyState::kFault);
    EXPECT_NE(gate.reason().find("joint 5"), std::string::npos) << gate.reason();
  }
}

TEST_F(SafetyGateTest, FaultWhileMovingBrakesWithinTheLimitsToAStandstill) {
  SafetyGate gate(config);
  start(gate, q0);
  const Vector6d target = q0 + (Vector6d() << 1.0, -0.5, 0.8, 1.0, -1.0, 1.0).finished();
  for (int i = 0; i < 150; ++i) follow(gate, target);
  const Vector6d v0 = gate.reference().qd;
  ASSERT_GT(v0.cwiseAbs().minCoeff(), 0.3);
  gate.fault("test fault");
  Checker check(gate);
  int stopped_at = -1;
  for (int i = 1; i <= 1000; ++i) {
    check.check(follow(gate, target));  // good targets keep coming: ignored
    if (stopped_at < 0 && gate.reference().qd.norm() == 0.0) stopped_at = i;
  }
  EXPECT_LE(check.worst_acceleration, 1.0 + 1e-9);
  double bound = 0;
  for (int j = 0; j < kDof; ++j) bound = std::max(bound, std::abs(v0[j]) / gate.reference_acceleration_limit()[j]);
  EXPECT_LE(stopped_at, bound * 1e3 + 1);
  EXPECT_EQ(gate.reason(), "test fault");
}

TEST_F(SafetyGateTest, RefusesConfigurationsThatCannotWork) {
  SafetyConfig bad = config;
  bad.approach_rate = 5000;  // above 2 / dt: the braking set would not be invariant
  EXPECT_THROW(SafetyGate{bad}, std::invalid_argument);
  bad = config;
  bad.max_acceleration[2] = 0;
  EXPECT_THROW(SafetyGate{bad}, std::invalid_argument);
  bad = config;
  bad.position_margin = 2.0;
  EXPECT_THROW(SafetyGate{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace wysiwyf::robot
