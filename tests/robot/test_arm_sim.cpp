// arm_sim through the Harness, on simulated time (1 ms ticks): servo step responses against
// every joint limit at every sample, holding under gravity, the watchdog, bad setpoints, poses
// beyond a joint limit, 20 ms and 1 ms setpoint streams, the fingertip pushing the plate, and
// repeatability. Measured figures are printed as "[measured] ..." lines.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "puma_model/puma_model.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {
namespace {

using robot::Matrix6d;
using robot::PumaModel;
using robot::Vector6d;

const std::string kUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf";
constexpr std::int64_t kMs = 1'000'000;
constexpr double kDt = 1e-3;
constexpr double kPi = 3.14159265358979323846;
// arm_sim's defaults, restated (the test must fail if they drift): the ready pose, the hard
// acceleration limits and the reference's share of the limits.
const Vector6d kReady =
    (Vector6d() << 0.255486131, -0.152351627, -2.593612368, 0.275843098, 1.188686600, -0.105157403).finished();
const Vector6d kAccelLimit = (Vector6d() << 8, 8, 10, 30, 30, 30).finished();
constexpr double kPositionMargin = 0.02;

const PumaModel& model() {
  static const PumaModel m(kUrdf, "dev");
  return m;
}

// A setpoint made at stamp_ns (the arm refuses stale and future ones).
msg::CartesianSetpoint setpoint(std::int64_t stamp_ns, const Eigen::Isometry3d& T,
                                const Eigen::Vector3d& v = Eigen::Vector3d::Zero(),
                                const Eigen::Vector3d& w = Eigen::Vector3d::Zero()) {
  msg::CartesianSetpoint s;
  s.header().stamp_ns(stamp_ns);
  s.header().frame_id("base");
  s.child_frame_id("dev");
  msgs::to_msg(T, s.pose());
  msgs::to_msg(v, w, s.twist());
  s.source("test");
  return s;
}

// One arm_sim in a Harness, every output recorded at every tick.
struct Sim {
  struct Sample {
    Vector6d q, qd, effort;
    Eigen::Isometry3d dev, hand;
    Eigen::Vector3d force, torque;
  };
  Harness h;
  Output<msg::CartesianSetpoint> sp;
  Output<msg::PoseStamped> hand_target;
  Input<msg::JointState> js;
  Input<msg::PoseStamped> dev, hand;
  Input<msg::WrenchStamped> wrench;
  Input<msg::RobotStatus> status;
  Output<msg::ArmRequest> request;
  msg::RobotStatus last_status;
  std::vector<Sample> samples;
  std::int64_t t = 0;

  explicit Sim(const std::string& params = "{}")
      : h("arm_sim", params, 1000),
        sp(h.feed<msg::CartesianSetpoint>("setpoint")),
        hand_target(h.feed<msg::PoseStamped>("hand_target")),
        js(h.watch<msg::JointState>("joint_state", 4)),
        dev(h.watch<msg::PoseStamped>("device_pose", 4)),
        hand(h.watch<msg::PoseStamped>("hand_pose", 4)),
        wrench(h.watch<msg::WrenchStamped>("wrench", 4)),
        status(h.watch<msg::RobotStatus>("status", 64)),
        request(h.feed<msg::ArmRequest>("request")) {
    h.activate();
  }

  // Ticks at t, then advances t by 1 ms.
  void tick() {
    h.tick(Time{t});
    t += kMs;
    msg::JointState j;
    msg::PoseStamped d, hp;
    msg::WrenchStamped w;
    ASSERT_TRUE(js.take(j));
    ASSERT_TRUE(dev.take(d));
    ASSERT_TRUE(hand.take(hp));
    ASSERT_TRUE(wrench.take(w));
    while (status.take(last_status)) {
    }
    Sample s;
    for (int k = 0; k < 6; ++k) {
      s.q[k] = j.position()[static_cast<std::size_t>(k)];
      s.qd[k] = j.velocity()[static_cast<std::size_t>(k)];
      s.effort[k] = j.effort()[static_cast<std::size_t>(k)];
    }
    s.dev = msgs::to_isometry(d.pose());
    s.hand = msgs::to_isometry(hp.pose());
    s.force = Eigen::Vector3d(w.wrench().force().x(), w.wrench().force().y(), w.wrench().force().z());
    s.torque = Eigen::Vector3d(w.wrench().torque().x(), w.wrench().torque().y(), w.wrench().torque().z());
    samples.push_back(s);
  }
  void send(const Eigen::Isometry3d& T, const Eigen::Vector3d& v = Eigen::Vector3d::Zero(),
            const Eigen::Vector3d& w = Eigen::Vector3d::Zero()) {
    sp.write(setpoint(t, T, v, w));  // made now
  }
  void send_hand(const Eigen::Vector3d& x) {
    msg::PoseStamped p;
    p.header().frame_id("base");
    p.child_frame_id("hand");
    p.pose().position().x(x.x());
    p.pose().position().y(x.y());
    p.pose().position().z(x.z());
    p.pose().orientation().w(1.0);
    hand_target.write(p);
  }
  // Streams a constant pose every `period_ms` for `ms` ticks.
  void hold_pose(const Eigen::Isometry3d& T, int ms, int period_ms = 20) {
    for (int i = 0; i < ms; ++i) {
      if ((t / kMs) % period_ms == 0) send(T);
      tick();
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  void ask_to_clear() {
    msg::ArmRequest r;
    fill_header(r.header(), t, 0, "base");
    r.request(msg::ARM_CLEAR_INPUT_FAULT);
    r.reason("test");
    request.write(r);
  }
  const Sample& last() const { return samples.back(); }
  int state() const { return static_cast<int>(last_status.state()); }
  std::string source() const { return last_status.source().c_str(); }
  std::string reason() const { return last_status.reason().c_str(); }
};

// Every sample from `from` on within the hard limits: position (URDF), velocity (URDF),
// acceleration (arm_sim's acceleration_limits, from successive velocity samples). Returns the
// worst share of each limit used.
struct LimitUse {
  double position_margin_left = 1e9;  // rad, smallest distance to a position limit
  double velocity = 0, acceleration = 0;
};
LimitUse check_limits(const std::vector<Sim::Sample>& s, std::size_t from = 1, bool motion = true) {
  LimitUse use;
  const auto& lim = model().limits();
  for (std::size_t i = std::max<std::size_t>(from, 1); i < s.size(); ++i) {
    for (int j = 0; j < 6; ++j) {
      const double q = s[i].q[j];
      EXPECT_GE(q, lim.lower[j]) << "joint " << j + 1 << " at " << i << " ms";
      EXPECT_LE(q, lim.upper[j]) << "joint " << j + 1 << " at " << i << " ms";
      use.position_margin_left = std::min(use.position_margin_left, std::min(q - lim.lower[j], lim.upper[j] - q));
      const double v = std::abs(s[i].qd[j]) / lim.velocity[j];
      const double a = std::abs(s[i].qd[j] - s[i - 1].qd[j]) / kDt / kAccelLimit[j];
      if (motion) {
        EXPECT_LE(v, 1.0) << "joint " << j + 1 << " velocity at " << i << " ms";
        EXPECT_LE(a, 1.0) << "joint " << j + 1 << " acceleration at " << i << " ms";
      }
      use.velocity = std::max(use.velocity, v);
      use.acceleration = std::max(use.acceleration, a);
    }
  }
  return use;
}

double max_abs_velocity(const Sim::Sample& s) { return s.qd.cwiseAbs().maxCoeff(); }

// The fingertip parked 2 cm in front of the plate, then driven 20 cm through it (100 N of
// impedance force) while the arm holds the ready pose with a 40 N force limit: the limit trips.
struct BlowToThePlate {
  static std::string params() {
    const Eigen::Vector3d p = park();
    char buf[256];
    std::snprintf(buf, sizeof buf, "{hand_park: [%.9f, %.9f, %.9f], force_limit: 40}", p.x(), p.y(), p.z());
    return buf;
  }
  static Eigen::Vector3d normal() { return model().fk(kReady).linear().col(2); }
  static Eigen::Vector3d park() { return model().fk(kReady) * Eigen::Vector3d(0.05, 0.04, 0.0) + 0.02 * normal(); }
  Sim sim{params()};
  BlowToThePlate() {
    const Eigen::Isometry3d ready = model().fk(kReady);
    sim.hold_pose(ready, 100);
    sim.send_hand(park() - 0.2 * normal());
    sim.hold_pose(ready, 1000);
  }
};

TEST(ArmSim, HoldsStillUnderGravityAtTheReadyPose) {
  Sim sim;
  for (int i = 0; i < 3000; ++i) sim.tick();
  double drift = 0, speed = 0, cart = 0;
  const Eigen::Vector3d p0 = model().fk(kReady).translation();
  for (const auto& s : sim.samples) {
    drift = std::max(drift, (s.q - kReady).cwiseAbs().maxCoeff());
    speed = std::max(speed, max_abs_velocity(s));
    cart = std::max(cart, (s.dev.translation() - p0).norm());
  }
  std::printf("[measured] at rest for 3 s: joint drift %.3g rad, speed %.3g rad/s, plate drift %.3g m\n", drift, speed,
              cart);
  EXPECT_LT(drift, 2e-4);  // about two encoder counts of joint 1
  EXPECT_LT(speed, 1e-3);
  EXPECT_LT(cart, 1e-4);
  EXPECT_EQ(sim.state(), msg::ARM_HOLDING);
  EXPECT_NE(sim.reason().find("waiting for the first setpoint"), std::string::npos) << sim.reason();
  EXPECT_EQ(sim.source(), "");
}

// A step of one joint, commanded as the pose it gives: the whole chain (tracker, IK, gate, servo).
class JointStep : public ::testing::TestWithParam<std::pair<int, double>> {};

TEST_P(JointStep, StaysWithinEveryLimitAtEverySampleAndSettles) {
  const auto [joint, delta] = GetParam();
  Sim sim("{max_setpoint_step: 0.5, max_setpoint_rotation: 1.5}");
  Vector6d goal = kReady;
  goal[joint] += delta;
  sim.hold_pose(model().fk(kReady), 100);
  sim.hold_pose(model().fk(goal), 2500);
  const LimitUse use = check_limits(sim.samples);
  const double error = (sim.last().q - goal).cwiseAbs().maxCoeff();
  const double cart = (sim.last().dev.translation() - model().fk(goal).translation()).norm();
  std::printf(
      "[measured] joint %d step %.2f rad: peak share of velocity limit %.3f, of acceleration limit %.3f, "
      "position limit distance %.3f rad; after 2.5 s joint error %.2g rad, plate error %.2g m\n",
      joint + 1, delta, use.velocity, use.acceleration, use.position_margin_left, error, cart);
  EXPECT_LT(error, 3e-4);  // settled: within three counts of joint 1's encoder
  EXPECT_LT(cart, 2e-4);
  EXPECT_LT(max_abs_velocity(sim.last()), 1e-3);
  EXPECT_NE(sim.state(), msg::ARM_FAULT) << sim.reason();
}

INSTANTIATE_TEST_SUITE_P(ArmSim, JointStep,
                         ::testing::Values(std::pair{0, 0.4}, std::pair{1, -0.3}, std::pair{2, 0.4}, std::pair{3, 1.2},
                                           std::pair{4, -0.8}, std::pair{5, 1.4}));

TEST(ArmSim, CartesianStepOf5cmStaysWithinLimitsAndSettles) {
  for (const Eigen::Vector3d& step :
       {Eigen::Vector3d(-0.05, 0, 0), Eigen::Vector3d(0, 0.05, 0), Eigen::Vector3d(0, 0, 0.05)}) {
    Sim sim;
    const Eigen::Isometry3d start = model().fk(kReady);
    Eigen::Isometry3d goal = start;
    goal.translation() += step;
    sim.hold_pose(start, 100);
    sim.hold_pose(goal, 1500);
    const LimitUse use = check_limits(sim.samples);
    const double cart = (sim.last().dev.translation() - goal.translation()).norm();
    const double turn = Eigen::AngleAxisd(Eigen::Matrix3d(sim.last().dev.linear() * goal.linear().transpose())).angle();
    // Time to settle within 0.5 mm of the goal, and overshoot past it along the step.
    int settle_ms = -1;
    double overshoot = 0;
    for (std::size_t i = 100; i < sim.samples.size(); ++i) {
      const Eigen::Vector3d e = sim.samples[i].dev.translation() - goal.translation();
      overshoot = std::max(overshoot, e.dot(step.normalized()));
      if (e.norm() > 5e-4)
        settle_ms = -1;
      else if (settle_ms < 0)
        settle_ms = static_cast<int>(i) - 100;
    }
    std::printf(
        "[measured] Cartesian step (%.2f %.2f %.2f) m: share of velocity limit %.3f, of acceleration "
        "limit %.3f; settled within 0.5 mm after %d ms, overshoot %.2g m; after 1.5 s error %.2g m, %.2g rad\n",
        step.x(), step.y(), step.z(), use.velocity, use.acceleration, settle_ms, overshoot, cart, turn);
    EXPECT_LT(cart, 2e-4);
    EXPECT_LT(turn, 1e-3);
    EXPECT_GT(settle_ms, 0);
    EXPECT_LT(settle_ms, 600);
    EXPECT_LT(overshoot, 1e-3);
    EXPECT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
    EXPECT_EQ(sim.source(), "test") << "the status names whose setpoints the arm follows";
  }
}

// A circle of radius `r` in the plate's plane (base y-z) at `hz`, streamed every `period_ms`
// with its twist.
void stream_circle(Sim& sim, int ms, int period_ms, double r = 0.03, double hz = 0.5) {
  const Eigen::Isometry3d centre = model().fk(kReady);
  const double w = 2 * kPi * hz;
  for (int i = 0; i < ms; ++i) {
    if ((sim.t / kMs) % period_ms == 0) {
      const double s = static_cast<double>(sim.t) * 1e-9;
      Eigen::Isometry3d T = centre;
      T.translation() += r * Eigen::Vector3d(0, std::sin(w * s), 1 - std::cos(w * s));
      sim.send(T, r * w * Eigen::Vector3d(0, std::cos(w * s), std::sin(w * s)));
    }
    sim.tick();
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(ArmSim, WatchdogBrakesToAHoldWhenSetpointsStop) {
  Sim sim;
  stream_circle(sim, 1500, 20, 0.05, 1.0);  // 0.31 m/s
  ASSERT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
  const double v0 = max_abs_velocity(sim.last());
  ASSERT_GT(v0, 0.2);
  const std::size_t stop = sim.samples.size();
  const std::int64_t last_setpoint_ms = (sim.t / kMs - 1) / 20 * 20;
  for (int i = 0; i < 1000; ++i) sim.tick();
  check_limits(sim.samples);
  // Stopped: every joint below 1 mrad/s from then on.
  std::size_t still = sim.samples.size();
  for (std::size_t i = sim.samples.size(); i-- > stop;) {
    if (max_abs_velocity(sim.samples[i]) > 1e-3) break;
    still = i;
  }
  const double stopped_ms = static_cast<double>(still) - static_cast<double>(last_setpoint_ms);
  // Bound: the timeout (60 ms), braking from the speed at the stop at the reference's
  // acceleration (the slowest joint: 0.8 * 8 rad/s^2), and 100 ms for the servo to settle.
  double braking_ms = 0;
  for (int j = 0; j < 6; ++j)
    braking_ms = std::max(braking_ms, std::abs(sim.samples[stop - 1].qd[j]) / (0.8 * kAccelLimit[j]) * 1e3);
  std::printf(
      "[measured] watchdog: speed %.3f rad/s when the setpoints stopped; still (< 1 mrad/s) %.0f ms after "
      "the last setpoint (bound %.0f ms)\n",
      v0, stopped_ms, 60 + braking_ms + 100);
  EXPECT_LT(stopped_ms, 60 + braking_ms + 100);
  EXPECT_EQ(sim.state(), msg::ARM_FAULT);
  EXPECT_TRUE(sim.last_status.clearable()) << "the stream's loss is the input's fault, not the arm's";
  EXPECT_NE(sim.reason().find("setpoint stream lost: no setpoint for"), std::string::npos) << sim.reason();
  // The stream coming back alone does not move the arm (a frozen display thawing mid-motion)...
  const Vector6d held = sim.last().q;
  sim.hold_pose(sim.last().dev, 300);
  EXPECT_EQ(sim.state(), msg::ARM_FAULT) << sim.reason();
  EXPECT_LT((sim.last().q - held).cwiseAbs().maxCoeff(), 2e-4);
  // ...the display's request does, from where it stopped.
  sim.ask_to_clear();
  sim.hold_pose(sim.last().dev, 300);
  EXPECT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
}

TEST(ArmSim, NanSetpointHoldsAndFaultsAndTheArmDoesNotMove) {
  Sim sim;
  const Eigen::Isometry3d ready = model().fk(kReady);
  sim.hold_pose(ready, 500);
  ASSERT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
  const Vector6d before = sim.last().q;
  Eigen::Isometry3d bad = ready;
  bad.translation().y() = std::numeric_limits<double>::quiet_NaN();
  sim.send(bad);
  sim.tick();
  Eigen::Isometry3d away = ready;
  away.translation().x() -= 0.05;  // good setpoints afterwards must not move it either
  sim.hold_pose(away, 1000);
  double moved = 0;
  for (std::size_t i = 500; i < sim.samples.size(); ++i)
    moved = std::max(moved, (sim.samples[i].q - before).cwiseAbs().maxCoeff());
  std::printf("[measured] NaN setpoint: largest joint motion afterwards %.3g rad; status '%s'\n", moved,
              sim.reason().c_str());
  EXPECT_EQ(sim.state(), msg::ARM_FAULT);
  EXPECT_NE(sim.reason().find("non-finite"), std::string::npos) << sim.reason();
  EXPECT_LT(moved, 2e-4);
}

TEST(ArmSim, NanWhileMovingBrakesWithinTheLimits) {
  Sim sim;
  stream_circle(sim, 1200, 20, 0.05, 1.0);
  msg::CartesianSetpoint bad = setpoint(sim.t, model().fk(kReady));
  bad.pose().orientation().w(std::numeric_limits<double>::infinity());
  sim.sp.write(bad);
  for (int i = 0; i < 800; ++i) sim.tick();
  check_limits(sim.samples);
  EXPECT_EQ(sim.state(), msg::ARM_FAULT);
  EXPECT_LT(max_abs_velocity(sim.last()), 1e-3);
}

TEST(ArmSim, ALostStreamHoldsWithinThreeOfItsPeriodsAndNoJointSpeedsUp) {
  // The plate accelerates at 1 m/s^2 along y (the second-order hold would extrapolate exactly
  // that) and the stream stops at 0.2 m/s. From the moment the next setpoint was due no joint may
  // go faster than it went then; the status says FAULT (held) within 3 periods of the last setpoint.
  for (const int period_ms : {1, 5, 20}) {
    Sim sim;
    const Eigen::Isometry3d ready = model().fk(kReady);
    sim.hold_pose(ready, 200, period_ms);
    const std::int64_t start = sim.t;
    std::int64_t last_setpoint = 0;
    std::size_t last_index = 0;
    for (int i = 0; i < 200; ++i) {  // 0.2 s at 1 m/s^2: 0.2 m/s, 2 cm
      if ((sim.t / kMs) % period_ms == 0) {
        const double s = static_cast<double>(sim.t - start) * 1e-9;
        Eigen::Isometry3d T = ready;
        T.translation().y() += 0.5 * s * s;
        sim.send(T, Eigen::Vector3d(0, s, 0));
        last_setpoint = sim.t, last_index = sim.samples.size();
      }
      sim.tick();
    }
    ASSERT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
    int held_after_ms = -1;
    for (int i = 0; i < 400; ++i) {
      sim.tick();
      if (held_after_ms < 0 && sim.state() == msg::ARM_FAULT)
        held_after_ms = static_cast<int>((sim.t - kMs - last_setpoint) / kMs);
    }
    check_limits(sim.samples);
    // Speeds at the moment the next setpoint was due, and the largest excess over them after.
    const std::size_t due = last_index + static_cast<std::size_t>(period_ms);
    const Vector6d at_due = sim.samples[due].qd.cwiseAbs();
    double excess = 0;
    for (std::size_t i = due; i < sim.samples.size(); ++i)
      excess = std::max(excess, (sim.samples[i].qd.cwiseAbs() - at_due).maxCoeff());
    std::printf(
        "[measured] %d ms stream lost at %.3f rad/s (fastest joint): held %d ms after the last setpoint; "
        "largest joint speed-up after the next was due %.2g rad/s; status '%s'\n",
        period_ms, at_due.maxCoeff(), held_after_ms, excess, sim.reason().c_str());
    EXPECT_GT(at_due.maxCoeff(), 0.1) << "the arm was moving";
    EXPECT_GT(held_after_ms, 0);
    EXPECT_LE(held_after_ms, 3 * period_ms + 1);
    EXPECT_LE(excess, 1e-3 + 0.01 * at_due.maxCoeff());
    EXPECT_NE(sim.reason().find("no setpoint for"), std::string::npos) << sim.reason();
    EXPECT_NE(sim.reason().find("from 'test'"), std::string::npos) << sim.reason();
    EXPECT_LT(max_abs_velocity(sim.last()), 1e-3) << "braked to a standstill";
  }
}

TEST(ArmSim, StaleFutureAndOutOfOrderSetpointsAreRefusedAndNeverMoveTheArm) {
  Sim sim;
  const Eigen::Isometry3d ready = model().fk(kReady);
  sim.hold_pose(ready, 300, 1);
  ASSERT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
  const Vector6d before = sim.last().q;
  Eigen::Isometry3d away = ready;
  away.translation().x() -= 0.05;  // a valid pose 5 cm off: followed if it got through
  // The good stream goes on at 1 kHz; after each good setpoint an intruder's with a bad stamp.
  // (-1: the largest stamp; -2: the smallest, whose age overflows an int64 difference.)
  const std::int64_t bad_stamps[] = {0, -1, -2, 60 * kMs /*stale*/, -10 * kMs /*future*/, kMs / 2 /*out of order*/};
  for (int i = 0; i < 500; ++i) {
    sim.send(ready);
    const std::int64_t offset = bad_stamps[i % 6];
    sim.sp.write(setpoint(offset == 0    ? 0
                          : offset == -1 ? std::numeric_limits<std::int64_t>::max()
                          : offset == -2 ? std::numeric_limits<std::int64_t>::min()
                                         : sim.t - offset,
                          away));
    sim.tick();
  }
  double moved = 0;
  for (std::size_t i = 300; i < sim.samples.size(); ++i)
    moved = std::max(moved, (sim.samples[i].q - before).cwiseAbs().maxCoeff());
  std::printf("[measured] 500 setpoints with bad stamps among good ones: %llu refused, joint motion %.3g rad\n",
              static_cast<unsigned long long>(sim.h.rejected("setpoint")), moved);
  EXPECT_EQ(sim.h.rejected("setpoint"), 500u);
  EXPECT_LT(moved, 2e-4);
  EXPECT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
  // Refused setpoints do not keep the arm alive: without the good stream it holds.
  for (int i = 0; i < 10; ++i) {
    sim.sp.write(setpoint(sim.t - 60 * kMs, away));
    sim.tick();
  }
  EXPECT_EQ(sim.state(), msg::ARM_FAULT) << sim.reason();
  EXPECT_NE(sim.reason().find("setpoint stream lost"), std::string::npos) << sim.reason();
}

TEST(ArmSim, AnInputFaultIsClearedOnRequestOnceTheArmStandsStillButTheArmsOwnIsNot) {
  Sim sim;
  stream_circle(sim, 1200, 1, 0.05, 1.0);
  Eigen::Isometry3d bad = sim.last().dev;
  bad.translation().y() = std::numeric_limits<double>::quiet_NaN();
  sim.send(bad);
  sim.tick();
  ASSERT_EQ(sim.state(), msg::ARM_FAULT);
  EXPECT_TRUE(sim.last_status.clearable()) << "a NaN setpoint is bad input";
  sim.ask_to_clear();  // still braking: refused, the fault stays
  sim.tick();
  EXPECT_EQ(sim.state(), msg::ARM_FAULT);
  EXPECT_EQ(sim.h.rejected("request"), 1u);
  for (int i = 0; i < 800; ++i) sim.tick();
  ASSERT_LT(max_abs_velocity(sim.last()), 1e-3);
  sim.ask_to_clear();
  sim.tick();
  EXPECT_EQ(sim.state(), msg::ARM_HOLDING) << sim.reason();
  EXPECT_FALSE(sim.last_status.clearable());
  EXPECT_NE(sim.reason().find("input fault cleared"), std::string::npos) << sim.reason();
  const Vector6d held = sim.last().q;
  for (int i = 0; i < 200; ++i) sim.tick();  // holding: nothing moves until a setpoint comes
  EXPECT_LT((sim.last().q - held).cwiseAbs().maxCoeff(), 2e-4);
  sim.hold_pose(sim.last().dev, 300, 1);  // a setpoint where the arm is: following again
  EXPECT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
  check_limits(sim.samples);

  // A fault of the arm itself (the measured force above its limit) is not cleared on request.
  BlowToThePlate blow;
  ASSERT_EQ(blow.sim.state(), msg::ARM_FAULT);
  EXPECT_FALSE(blow.sim.last_status.clearable());
  blow.sim.ask_to_clear();
  blow.sim.tick();
  EXPECT_EQ(blow.sim.state(), msg::ARM_FAULT);
  EXPECT_EQ(blow.sim.h.rejected("request"), 1u);
}

TEST(ArmSim, CommandingAPoseBeyondAJointLimitNeverExceedsIt) {
  // Joint 5 driven past +100 deg at 0.5 rad/s, as poses, every 20 ms.
  Sim sim;
  Vector6d q = kReady;
  const auto& lim = model().limits();
  double peak = -1e9;
  for (int i = 0; i < 3000; ++i) {
    if ((sim.t / kMs) % 20 == 0) {
      q[4] = std::min(kReady[4] + 0.5 * static_cast<double>(sim.t) * 1e-9, 2.3);
      sim.send(model().fk(q));
    }
    sim.tick();
    peak = std::max(peak, sim.last().q[4]);
  }
  check_limits(sim.samples);
  std::printf(
      "[measured] joint 5 driven to %.3f rad: peak %.4f rad (limit %.4f, reference stops at %.4f); "
      "status '%s'\n",
      q[4], peak, lim.upper[4], lim.upper[4] - kPositionMargin, sim.reason().c_str());
  EXPECT_LE(peak, lim.upper[4] - kPositionMargin + 1e-3);
  EXPECT_GT(peak, lim.upper[4] - kPositionMargin - 0.05);  // it did go up to the limit
  EXPECT_EQ(sim.state(), msg::ARM_FAULT);
  EXPECT_NE(sim.reason().find("inverse kinematics"), std::string::npos) << sim.reason();
}

// The smoothness measure: largest change of joint acceleration from one ms to the next (from the
// velocity samples), in the steady part.
struct Smoothness {
  double max_accel = 0, max_accel_step = 0;
};
Smoothness smoothness(const std::vector<Sim::Sample>& s, std::size_t from) {
  Smoothness out;
  for (std::size_t i = from; i < s.size(); ++i) {
    const Vector6d a = (s[i].qd - s[i - 1].qd) / kDt, a_prev = (s[i - 1].qd - s[i - 2].qd) / kDt;
    out.max_accel = std::max(out.max_accel, a.cwiseAbs().maxCoeff());
    out.max_accel_step = std::max(out.max_accel_step, (a - a_prev).cwiseAbs().maxCoeff());
  }
  return out;
}

// The same circle streamed every 20 ms and every 1 ms.
struct CircleRuns {
  Smoothness s20, s1;
  double apart = 0, track20 = 0, track1 = 0;
};
CircleRuns run_circles(const std::string& params) {
  CircleRuns out;
  Sim slow(params), fast(params);
  stream_circle(slow, 4000, 20);
  stream_circle(fast, 4000, 1);
  check_limits(slow.samples);
  check_limits(fast.samples);
  EXPECT_EQ(slow.state(), msg::ARM_OK) << slow.reason();
  EXPECT_EQ(fast.state(), msg::ARM_OK) << fast.reason();
  out.s20 = smoothness(slow.samples, 1000);
  out.s1 = smoothness(fast.samples, 1000);
  const Eigen::Isometry3d centre = model().fk(kReady);
  const double w = 2 * kPi * 0.5;
  for (std::size_t i = 1000; i < slow.samples.size(); ++i) {
    out.apart = std::max(out.apart, (slow.samples[i].q - fast.samples[i].q).cwiseAbs().maxCoeff());
    const double t = static_cast<double>(i) * 1e-3;
    const Eigen::Vector3d path = centre.translation() + 0.03 * Eigen::Vector3d(0, std::sin(w * t), 1 - std::cos(w * t));
    out.track20 = std::max(out.track20, (slow.samples[i].dev.translation() - path).norm());
    out.track1 = std::max(out.track1, (fast.samples[i].dev.translation() - path).norm());
  }
  std::printf(
      "[measured] circle r 3 cm at 0.5 Hz, %s: peak joint acceleration %.3f / %.3f rad/s^2 (20 ms / 1 ms "
      "setpoints), largest 1-ms change of acceleration %.3f / %.3f rad/s^2; joint traces %.3g rad apart; "
      "path error %.3g / %.3g m\n",
      params.c_str(), out.s20.max_accel, out.s1.max_accel, out.s20.max_accel_step, out.s1.max_accel_step, out.apart,
      out.track20, out.track1);
  return out;
}

TEST(ArmSim, SetpointsAt20msAnd1msBothGiveASmoothJointTrajectory) {
  // Without encoder quantisation the joint trajectory shows what the trajectory generator makes
  // of the two streams: continuous velocity, the same peak acceleration (the path's own, far
  // below the limits) changing little from one ms to the next (no 50 Hz kicks: the 20 ms stream
  // is extrapolated with the acceleration its twists imply), the same trajectory from both, on
  // the path.
  const CircleRuns ideal = run_circles("{encoder_counts: 0}");
  for (const Smoothness& s : {ideal.s20, ideal.s1}) {
    EXPECT_LT(s.max_accel, 1.0);
    EXPECT_LT(s.max_accel_step, 0.3);
  }
  EXPECT_NEAR(ideal.s20.max_accel, ideal.s1.max_accel, 0.05);
  EXPECT_LT(ideal.apart, 1e-4);
  EXPECT_LT(ideal.track20, 5e-4);
  EXPECT_LT(ideal.track1, 5e-4);
  // With the encoders, each count the servo sees is a small torque step: a bounded jitter on top.
  const CircleRuns real = run_circles("{}");
  for (const Smoothness& s : {real.s20, real.s1}) {
    EXPECT_LT(s.max_accel, 1.5);
    EXPECT_LT(s.max_accel_step, 1.0);
  }
  EXPECT_LT(real.apart, 5e-4);
  EXPECT_LT(real.track20, 5e-4);
  EXPECT_LT(real.track1, 5e-4);
}

TEST(ArmSim, TheHandPushingThePlateIsMeasuredAndStoppedByIt) {
  // The hand waits 2 cm in front of the plate, then is driven to 3 cm behind its face.
  const Eigen::Isometry3d ready = model().fk(kReady);
  const Eigen::Vector3d on_plate = ready * Eigen::Vector3d(0.05, 0.04, 0.0);  // off the knob
  const Eigen::Vector3d n = ready.linear().col(2);                            // plate normal
  const Eigen::Vector3d park = on_plate + 0.02 * n;
  char params[256];
  std::snprintf(params, sizeof params, "{hand_park: [%.9f, %.9f, %.9f]}", park.x(), park.y(), park.z());
  Sim sim(params);
  const double k_hand = 500, radius = 0.01, k_contact = 20000, tool_mass = 1.08 + 0.0763;
  Eigen::Vector3d target = park;
  double deepest = -1;
  for (int i = 0; i < 2500; ++i) {
    if ((sim.t / kMs) % 20 == 0) sim.send(ready);
    if (i >= 200 && i <= 700) {  // in 0.5 s from 2 cm in front to 3 cm behind the face
      target = park - (0.05 * (i - 200) / 500.0) * n;
      sim.send_hand(target);
    }
    sim.tick();
    const Eigen::Vector3d in_dev = sim.last().dev.inverse() * sim.last().hand.translation();
    deepest = std::max(deepest, radius - in_dev.z());
  }
  check_limits(sim.samples);
  // Averages over the last 200 ms (the noise is 0.05 N per axis).
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero(), hand = Eigen::Vector3d::Zero();
  for (std::size_t i = sim.samples.size() - 200; i < sim.samples.size(); ++i) {
    force += sim.samples[i].force / 200.0;
    torque += sim.samples[i].torque / 200.0;
    hand += sim.samples[i].hand.translation() / 200.0;
  }
  // Expected: the fingertip at rest, so the contact force equals its impedance force, and the
  // sensor reads that push plus the tool's weight, in the sensor frame (axes of dev, 2 cm behind).
  const Eigen::Vector3d push = k_hand * (target - hand);  // on the plate, base frame
  const Eigen::Isometry3d sensor = model().fk(sim.last().q, model().frame("ft_sensor"));
  const Eigen::Matrix3d Rt = sensor.linear().transpose();
  const Eigen::Vector3d weight = tool_mass * Eigen::Vector3d(0, 0, -9.81);
  const Eigen::Vector3d expected_force = Rt * (push + weight);
  const Eigen::Vector3d contact = hand - radius * n;  // on the plate face
  const Eigen::Vector3d com = sensor * Eigen::Vector3d(0, 0, (1.08 * 0.015 + 0.0763 * 0.04) / tool_mass);
  const Eigen::Vector3d expected_torque =
      Rt * ((contact - sensor.translation()).cross(push) + (com - sensor.translation()).cross(weight));
  const Eigen::Vector3d in_dev = sim.last().dev.inverse() * hand;
  const double penetration = radius - in_dev.z();
  std::printf(
      "[measured] hand push: contact force %.3f N; sensor force error %.3g N, torque error %.3g N m; "
      "penetration at rest %.3g m (push / k_contact = %.3g m), deepest %.3g m; hand speed %.3g m/s\n",
      push.norm(), (force - expected_force).norm(), (torque - expected_torque).norm(), penetration,
      push.norm() / k_contact, deepest,
      (sim.samples.back().hand.translation() - sim.samples[sim.samples.size() - 2].hand.translation()).norm() / kDt);
  EXPECT_GT(push.dot(-n), 15.0);  // it does push: 500 N/m * (3 cm + 1 cm radius - what the plate gives)
  EXPECT_LT((force - expected_force).norm(), 0.05);
  EXPECT_LT((torque - expected_torque).norm(), 5e-3);
  EXPECT_NEAR(penetration, push.norm() / k_contact, 2e-4);
  EXPECT_LT(deepest, 2.5e-3);  // stopped by the plate: never more than 2.5 mm in
  EXPECT_NE(sim.state(), msg::ARM_FAULT) << sim.reason();
  // The plate gives a little under the push (the servo's stiffness), and holds it.
  const double gives = (sim.last().dev.translation() - ready.translation()).norm();
  std::printf("[measured] the plate gives %.3g m under the push\n", gives);
  EXPECT_LT(gives, 2e-3);
}

TEST(ArmSim, AHardBlowTripsTheForceLimit) {
  BlowToThePlate blow;
  // The blow itself accelerates the arm beyond what the servo would: only positions are checked.
  check_limits(blow.sim.samples, 1, false);
  EXPECT_EQ(blow.sim.state(), msg::ARM_FAULT);
  EXPECT_NE(blow.sim.reason().find("measured force"), std::string::npos) << blow.sim.reason();
}

TEST(ArmSim, TwoRunsGiveIdenticalTraces) {
  auto run = [](std::vector<Sim::Sample>& out) {
    const Eigen::Isometry3d ready = model().fk(kReady);
    Sim sim("{seed: 42}");
    for (int i = 0; i < 1500; ++i) {
      if (i == 300) sim.send_hand(ready * Eigen::Vector3d(0.05, 0.0, -0.02));
      if ((sim.t / kMs) % 20 == 0) {
        Eigen::Isometry3d T = ready;
        T.translation().y() += 0.02 * std::sin(static_cast<double>(sim.t) * 1e-9 * 3);
        sim.send(T);
      }
      sim.tick();
    }
    out = sim.samples;
  };
  std::vector<Sim::Sample> a, b;
  run(a);
  run(b);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].q, b[i].q) << i;
    ASSERT_EQ(a[i].qd, b[i].qd) << i;
    ASSERT_EQ(a[i].effort, b[i].effort) << i;
    ASSERT_EQ(a[i].force, b[i].force) << i;
    ASSERT_EQ(a[i].hand.translation(), b[i].hand.translation()) << i;
  }
  EXPECT_GT((a.back().force - a.front().force).norm(), 1.0);  // the hand did touch
}

TEST(ArmSim, RefusesParametersThatDoNotFit) {
  EXPECT_ANY_THROW(Sim("{initial_q: [0, 0, 0, 0, 0]}"));
  EXPECT_ANY_THROW(Sim("{initial_q: [0, 0, 0, 0, 2.0, 0]}"));  // joint 5 beyond +100 deg
}

}  // namespace
}  // namespace wysiwyf::test
