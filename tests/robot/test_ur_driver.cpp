// ur_driver against the UR emulator (libs/robot/ur_controller_emulator, in this process, on loopback),
// on the simulated clock in lockstep: the same setpoint stream gives the same joint trajectory as
// arm_sim with the UR5e's URDF; every injected fault (a protective stop, dropped connections,
// outputs late beyond 3 periods, a package cut short) holds the arm within 3 periods and is
// named in its status; after a protective stop it stays held until the supervisor's clear
// request, then recovers. Measured figures are printed as "[measured]" lines.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "arm_model/arm_model.hpp"
#include "arm_under_test.hpp"
#include "ur_controller_emulator/ur_emulator.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {
namespace {

using robot::JointVector;
using robot::ur::UrEmulator;
using Vector6d = Eigen::Matrix<double, 6, 1>;

const std::string kUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/ur5e.urdf";
constexpr std::int64_t kMs = 1'000'000;
constexpr int kTickMs = 2;  // 500 Hz: the e-Series' period
// config/pipelines/robots/ur5e-sim.yaml's arm: the parked pose, ideal drives, the PUMA's
// acceleration limits (UR publishes none). The emulator parks there by default.
const std::string kArmParams = "urdf: " + kUrdf + ", acceleration_limits: [8, 8, 10, 30, 30, 30]";
const std::string kSimParams =
    "{drive: \"\", initial_q: [2.802180, -1.581828, 1.807510, -0.225596, 1.231347, 1.570657], " + kArmParams + "}";

const robot::ArmModel& model() {
  static const robot::ArmModel m(kUrdf, "dev");
  return m;
}

UrEmulator::Options lockstep_options() {
  UrEmulator::Options o;
  o.lockstep = true;
  o.controller.urdf = kUrdf;
  return o;
}

std::string driver_params(const UrEmulator& e, const std::string& more = "") {
  return "{lockstep: true, reply_timeout: 0.02, rtde_port: " + std::to_string(e.rtde_port()) +
         ", script_port: " + std::to_string(e.script_port()) +
         ", dashboard_port: " + std::to_string(e.dashboard_port()) + ", " + kArmParams + more + "}";
}

// The setpoint due at `ms`, if any: the circle around the parked plate.
bool setpoint_at(int ms, int period_ms, msg::CartesianSetpoint& out) {
  JointVector q0(6);
  q0 << 2.802180, -1.581828, 1.807510, -0.225596, 1.231347, 1.570657;
  return circle_setpoint_at(ms, period_ms, model().fk(q0), out);
}

// One arm component (arm_sim or ur_driver) at 500 Hz, with the stream of setpoint_at().
struct Arm : test::ArmUnderTest {
  Arm(const std::string& type, const std::string& params) : ArmUnderTest(type, params, 1000.0 / kTickMs) {}
  int ms() const { return static_cast<int>(t / kMs); }
  // A tick with the setpoint stream's sample due now (every `period_ms`).
  void follow(int period_ms) {
    msg::CartesianSetpoint s;
    tick(setpoint_at(ms(), period_ms, s) ? &s : nullptr);
  }
  void hold_here() {
    const msg::CartesianSetpoint s = setpoint(t, model().fk(JointVector(q.back())));
    tick(ms() % 20 == 0 ? &s : nullptr);
  }
};

Difference run_both(int ms, int period_ms) {
  UrEmulator emulator(lockstep_options());
  Arm sim("arm_sim", kSimParams);
  Arm driver("ur_driver", driver_params(emulator));
  for (int i = 0; i < ms / kTickMs; ++i) {
    sim.follow(period_ms);
    driver.follow(period_ms);
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
  EXPECT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
  EXPECT_EQ(sim.q.size(), static_cast<std::size_t>(ms / kTickMs));
  EXPECT_EQ(driver.q.size(), static_cast<std::size_t>(ms / kTickMs));
  const Difference d = compare(sim, driver);
  EXPECT_GT(d.travel, 0.02) << "the arm should have moved";
  EXPECT_EQ(emulator.counters().packages_refused, 0u);
  std::printf(
      "[measured] %d ms of setpoints every %d ms: arm_sim (UR5e) vs ur_driver + UR emulator, largest difference "
      "%.3g rad, %.3g rad/s, %.3g N m (joint travel %.3f rad)\n",
      ms, period_ms, d.q, d.qd, d.effort, d.travel);
  return d;
}

TEST(UrDriver, FollowsTheSameJointTrajectoryAsArmSimWithTheUr5e) {
  // The driver and arm_sim share the setpoint follower and the gate; the emulator and arm_sim
  // share the servo and the arm; RTDE carries doubles unchanged: the same arithmetic in the
  // same order, so the trajectories agree to the last bit.
  for (int period : {20, 2}) {
    const Difference d = run_both(3000, period);
    EXPECT_EQ(d.q, 0.0);
    EXPECT_EQ(d.qd, 0.0);
    EXPECT_EQ(d.effort, 0.0);
  }
}

// A driver following the stream for 1.5 s, then `inject`: the arm holds within 3 periods, its
// status names `expected`, it publishes nothing stale and the emulated arm stays where it was.
void holds_on(const std::string& fault, const std::function<void(UrEmulator&)>& inject, const std::string& expected) {
  SCOPED_TRACE(fault);
  UrEmulator emulator(lockstep_options());
  Arm driver("ur_driver", driver_params(emulator));
  for (int i = 0; i < 750; ++i) driver.follow(20);
  ASSERT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
  inject(emulator);
  int held_after = -1;
  for (int i = 0; i < 50; ++i) {
    driver.follow(20);
    if (held_after < 0 && driver.state() == msg::ARM_FAULT) held_after = i;
  }
  const JointVector held = emulator.true_q();
  for (int i = 0; i < 200; ++i) driver.follow(20);
  std::printf("[measured] %s: held after %d periods (reason: %s)\n", fault.c_str(), held_after,
              driver.reason().c_str());
  EXPECT_EQ(driver.state(), msg::ARM_FAULT);
  EXPECT_GE(held_after, 0);
  EXPECT_LE(held_after, 3);
  EXPECT_NE(driver.reason().find(expected), std::string::npos) << driver.reason();
  EXPECT_EQ(driver.h.health(), Health::kFault);
  EXPECT_LT((emulator.true_q() - held).cwiseAbs().maxCoeff(), 2e-3) << "the arm holds while the stream goes on";
}

TEST(UrDriver, EveryInjectedFaultHoldsTheArmWithinThreePeriodsAndIsNamed) {
  holds_on(
      "protective stop", [](UrEmulator& e) { e.protective_stop("test: a collision"); }, "PROTECTIVE_STOP");
  holds_on(
      "dropped connections", [](UrEmulator& e) { e.drop_connections(); }, "closed the connection");
  holds_on(
      "outputs 5 periods late", [](UrEmulator& e) { e.delay_outputs(5); }, "no output package");
  holds_on(
      "a package cut short", [](UrEmulator& e) { e.send_malformed(); }, "cut short");
}

TEST(UrDriver, APackageCutShortIsRefusedCountedAndTheLinkReopened) {
  UrEmulator emulator(lockstep_options());
  Arm driver("ur_driver", driver_params(emulator));
  for (int i = 0; i < 100; ++i) driver.follow(20);
  const std::uint64_t warnings = driver.h.warnings();
  emulator.send_malformed();
  for (int i = 0; i < 100; ++i) driver.follow(20);
  EXPECT_EQ(driver.h.warnings(), warnings + 1) << "one refused package, counted";
  EXPECT_EQ(emulator.counters().rtde_connections, 2u) << "reconnected";
  EXPECT_GE(driver.published, 1) << "measurements come again on the new connection";
  EXPECT_EQ(driver.state(), msg::ARM_FAULT);
}

TEST(UrDriver, AfterAProtectiveStopItHoldsUntilTheSupervisorClearsThenRecovers) {
  UrEmulator emulator(lockstep_options());
  Arm driver("ur_driver", driver_params(emulator));
  for (int i = 0; i < 750; ++i) driver.follow(20);
  ASSERT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
  emulator.protective_stop("test: a collision");
  for (int i = 0; i < 500; ++i) driver.follow(20);  // a second of setpoints: nothing moves
  EXPECT_EQ(driver.state(), msg::ARM_FAULT);
  EXPECT_EQ(emulator.safety_mode(), robot::rtde::SafetyMode::kProtectiveStop) << "the driver unlocks nothing by itself";
  const JointVector stopped = emulator.true_q();

  driver.clear("test: the collision is gone");
  for (int i = 0; i < 100 && driver.state() != msg::ARM_HOLDING; ++i) driver.hold_here();
  EXPECT_EQ(driver.state(), msg::ARM_HOLDING) << driver.reason();
  EXPECT_EQ(emulator.safety_mode(), robot::rtde::SafetyMode::kNormal);
  EXPECT_EQ(emulator.program_state(), robot::rtde::follow::ProgramState::kFollowing);
  EXPECT_LT((emulator.true_q() - stopped).cwiseAbs().maxCoeff(), 2e-3) << "holds where it stopped";
  for (int i = 0; i < 100; ++i) driver.hold_here();
  EXPECT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
}

// In real time, a dashboard that takes the connection and never answers: the recovery waits for
// it off the tick, which goes on every period (the hold package) until the recovery gives up,
// and the request is refused saying why; the arm holds throughout. Ticked at the controller's
// 2 ms on the wall clock against the emulator's own; the stream may miss 100 ms before it counts
// as lost (a loaded test machine is not a real-time one).
TEST(UrDriver, InRealTimeASilentDashboardDoesNotHoldUpTheTick) {
  UrEmulator::Options options = lockstep_options();
  options.lockstep = false;
  UrEmulator emulator(options);
  Arm driver("ur_driver",
             "{lockstep: false, stream_timeout_periods: 50, connect_timeout: 0.5, rtde_port: " +
                 std::to_string(emulator.rtde_port()) + ", script_port: " + std::to_string(emulator.script_port()) +
                 ", dashboard_port: " + std::to_string(emulator.dashboard_port()) + ", " + kArmParams + "}");
  using Wall = std::chrono::steady_clock;
  auto next = Wall::now();
  double longest = 0;  // s: the longest tick after the clear
  auto run = [&](int ticks, bool timed) {
    for (int i = 0; i < ticks; ++i) {
      std::this_thread::sleep_until(next += std::chrono::milliseconds(kTickMs));
      const auto start = Wall::now();
      driver.follow(20);  // (the gate holds while the arm is faulted)
      if (timed) longest = std::max(longest, std::chrono::duration<double>(Wall::now() - start).count());
    }
  };
  run(250, false);
  ASSERT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
  emulator.protective_stop("test: a collision");
  run(50, false);
  ASSERT_EQ(driver.state(), msg::ARM_FAULT);
  emulator.silence_dashboard();
  driver.clear("test: the collision is gone");
  run(500, true);  // 1 s: the 0.5 s the recovery waits, and after
  EXPECT_EQ(driver.h.rejected("request"), 1u) << "the recovery should have given up after its 0.5 s";
  EXPECT_LT(longest, 0.25) << "a tick waited for the dashboard";
  EXPECT_EQ(driver.state(), msg::ARM_FAULT) << driver.reason();
  EXPECT_EQ(emulator.safety_mode(), robot::rtde::SafetyMode::kProtectiveStop);
  std::printf("[measured] the longest tick while the silent dashboard was waited for: %.2f ms\n", longest * 1e3);
}

TEST(UrDriver, TheTcpForceIsTheWristReadingOfTheToolInTheSensorFrame) {
  // The emulated sensor reads no load (the pendant's payload compensated): the reading is the
  // tool's weight put back, in ft_sensor about its origin, as arm_sim's noiseless wrist sensor
  // reads the same tool (its mass and centre from the URDF; the scene's tool_mass 1.1563 kg
  // 0.01665 m beyond ft_sensor, which is 0.03 m along the flange).
  UrEmulator emulator(lockstep_options());
  Arm driver("ur_driver", driver_params(emulator, ", tcp_force: true, tcp_payload: [1.1563, 0, 0, 0.04665]"));
  Arm sim("arm_sim", kSimParams.substr(0, kSimParams.size() - 1) + ", ft_noise_force: 0, ft_noise_torque: 0}");
  Input<msg::WrenchStamped> from_driver = driver.h.watch<msg::WrenchStamped>("wrench", 4);
  Input<msg::WrenchStamped> from_sim = sim.h.watch<msg::WrenchStamped>("wrench", 4);
  driver.tick();
  sim.tick();
  msg::WrenchStamped d, s;
  ASSERT_TRUE(from_driver.take(d));
  ASSERT_TRUE(from_sim.take(s));
  EXPECT_EQ(std::string(d.header().frame_id().c_str()), "ft_sensor");
  const Eigen::Vector3d fd = msgs::to_eigen(d.wrench().force()), fs = msgs::to_eigen(s.wrench().force());
  const Eigen::Vector3d td = msgs::to_eigen(d.wrench().torque()), ts = msgs::to_eigen(s.wrench().torque());
  std::printf(
      "[measured] TCP force %.4f %.4f %.4f N, %.4f %.4f %.4f N m; arm_sim's sensor %.4f %.4f %.4f N, %.4f %.4f "
      "%.4f N m\n",
      fd.x(), fd.y(), fd.z(), td.x(), td.y(), td.z(), fs.x(), fs.y(), fs.z(), ts.x(), ts.y(), ts.z());
  EXPECT_NEAR(fd.norm(), 1.1563 * 9.81, 1e-9);
  EXPECT_LT((fd - fs).norm(), 1e-3);
  EXPECT_LT((td - ts).norm(), 1e-3);
}

TEST(UrDriver, NoControllerIsAClearActivationError) {
  std::uint16_t free_port;
  {
    UrEmulator probe(lockstep_options());  // ports that were free a moment ago
    free_port = probe.rtde_port();
  }
  try {
    Harness h("ur_driver", "{connect_timeout: 0.1, lockstep: false, rtde_port: " + std::to_string(free_port) +
                               ", script_port: " + std::to_string(free_port) + ", " + kArmParams + "}");
    h.activate();
    FAIL() << "activated without a controller";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(free_port)), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wysiwyf::test
