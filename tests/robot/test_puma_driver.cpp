// puma_driver against apps/puma-link-emulator's controller (in this process, on loopback), on the
// simulated clock: the same setpoint stream gives the same joint trajectory as arm_sim; a lost
// link holds and faults, and recovers; no controller is a clear activation error. And the
// emulated controller alone: it refuses commands beyond the limits, drops damaged and stale
// datagrams, and holds when commands stop. Measured figures are printed as "[measured]" lines.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "arm_under_test.hpp"
#include "link_client.hpp"
#include "puma_controller_emulator/controller_emulator.hpp"
#include "puma_model/puma_model.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {
namespace {

using robot::PumaModel;
using robot::Vector6d;
using robot::link::ControllerEmulator;
using robot::link::LinkClient;

const std::string kUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf";
constexpr std::int64_t kMs = 1'000'000;
// arm_sim's and the emulator's default start: the ready pose.
const Vector6d kReady =
    (Vector6d() << 0.255486131, -0.152351627, -2.593612368, 0.275843098, 1.188686600, -0.105157403).finished();

const PumaModel& model() {
  static const PumaModel m(kUrdf, "dev");
  return m;
}

ControllerEmulator::Options lockstep_options() {
  ControllerEmulator::Options o;
  o.lockstep = true;
  o.urdf = kUrdf;
  o.drive = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560_drive.yaml";
  return o;
}

// The setpoint due at tick `ms`, if any: the circle around the ready pose.
bool setpoint_at(int ms, int period_ms, msg::CartesianSetpoint& out) {
  return circle_setpoint_at(ms, period_ms, model().fk(kReady), out);
}

using Arm = test::ArmUnderTest;  // arm_sim or puma_driver at 1 kHz

Difference run_both(int ms, int period_ms) {
  ControllerEmulator controller(lockstep_options());
  Arm sim("arm_sim", "{}");
  Arm driver("puma_driver", "{lockstep: true, port: " + std::to_string(controller.port()) + "}");
  msg::CartesianSetpoint s;
  for (int i = 0; i < ms; ++i) {
    const bool due = setpoint_at(i, period_ms, s);
    sim.tick(due ? &s : nullptr);
    driver.tick(due ? &s : nullptr);
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_EQ(sim.state(), msg::ARM_OK) << sim.reason();
  EXPECT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
  EXPECT_EQ(sim.q.size(), static_cast<std::size_t>(ms));
  EXPECT_EQ(driver.q.size(), static_cast<std::size_t>(ms));
  const Difference d = compare(sim, driver);
  EXPECT_GT(d.travel, 0.02) << "the arm should have moved";
  std::printf(
      "[measured] %d ms of setpoints every %d ms: arm_sim vs puma_driver + emulator, largest difference "
      "%.3g rad, %.3g rad/s, %.3g N m (joint travel %.3f rad)\n",
      ms, period_ms, d.q, d.qd, d.effort, d.travel);
  return d;
}

TEST(PumaDriver, FollowsTheSameJointTrajectoryAsArmSim) {
  // The driver and arm_sim share the setpoint follower and the gate; the emulator and arm_sim
  // share the servo and the arm; puma-link carries doubles unchanged. Stated tolerance: 1e-9 rad
  // (what is measured is 0: the same arithmetic in the same order).
  for (int period : {20, 1}) {
    const Difference d = run_both(3000, period);
    EXPECT_LE(d.q, 1e-9);
    EXPECT_LE(d.qd, 1e-9);
    EXPECT_LE(d.effort, 1e-6);
  }
}

TEST(PumaDriver, ALostLinkHoldsAndFaultsAndARestoredOneHoldsAtTheArm) {
  ControllerEmulator controller(lockstep_options());
  Arm driver("puma_driver", "{lockstep: true, reply_timeout: 0.02, port: " + std::to_string(controller.port()) + "}");
  msg::CartesianSetpoint s;
  for (int i = 0; i < 1500; ++i) driver.tick(setpoint_at(i, 20, s) ? &s : nullptr);
  ASSERT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
  const Vector6d q_before = controller.true_q();

  controller.set_silent(true);  // the cable is pulled
  int lost_after = -1, published_while_lost = 0;
  for (int i = 1500; i < 1520; ++i) {
    driver.tick(setpoint_at(i, 20, s) ? &s : nullptr);
    if (lost_after < 0 && driver.state() == msg::ARM_FAULT) lost_after = i - 1500;
    if (lost_after >= 0) published_while_lost += driver.published;
  }
  std::printf("[measured] link lost after %d ticks without an answer (reason: %s)\n", lost_after,
              driver.reason().c_str());
  EXPECT_EQ(driver.state(), msg::ARM_FAULT);
  EXPECT_NE(driver.reason().find("puma-link"), std::string::npos) << driver.reason();
  EXPECT_LE(lost_after, 4);
  EXPECT_EQ(published_while_lost, 0) << "no stale joint states while the link is down";
  // (lockstep: the emulated arm did not move while it heard nothing)
  EXPECT_LT((controller.true_q() - q_before).cwiseAbs().maxCoeff(), 0.01);

  controller.set_silent(false);  // plugged in again: the commands carry the hold flag
  for (int i = 1520; i < 1600; ++i) driver.tick();
  EXPECT_EQ(driver.state(), msg::ARM_HOLDING) << driver.reason();
  const Vector6d held = controller.true_q();
  for (int i = 1600; i < 1700; ++i) driver.tick();
  EXPECT_LT((controller.true_q() - held).cwiseAbs().maxCoeff(), 1e-3) << "holds where it is";
  // A setpoint where the arm is resumes following.
  const Eigen::Isometry3d here = model().fk(driver.q.back());
  for (int i = 1700; i < 1800; ++i) {
    const msg::CartesianSetpoint hold_here = setpoint(i * kMs, here);
    driver.tick(i % 20 == 0 ? &hold_here : nullptr);
  }
  EXPECT_EQ(driver.state(), msg::ARM_OK) << driver.reason();
}

TEST(PumaDriver, NoControllerIsAClearActivationError) {
  std::uint16_t free_port;
  {
    ControllerEmulator probe(lockstep_options());  // a port that was free a moment ago
    free_port = probe.port();
  }
  try {
    Harness h("puma_driver", "{connect_timeout: 0.1, port: " + std::to_string(free_port) + "}");
    h.activate();
    FAIL() << "activated without a controller";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("no answer from the controller at 127.0.0.1:" + std::to_string(free_port)),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(Harness("puma_driver", "{host: puma.lab}").activate(), std::exception);
}

// A bare host for the emulator tests.
struct Host {
  ControllerEmulator& controller;
  LinkClient client;
  robot::link::State state;
  explicit Host(ControllerEmulator& c) : controller(c), client("127.0.0.1", c.port()) {}
  bool command(robot::link::Command c) {
    const std::uint32_t seq = client.send(c);
    return client.wait_for_ack(seq, std::chrono::seconds(2), state);
  }
  robot::link::Command at(const Vector6d& q) const {
    robot::link::Command c;
    for (int j = 0; j < 6; ++j) c.q[static_cast<std::size_t>(j)] = q[j];
    return c;
  }
  Vector6d q() const {
    Vector6d v;
    for (int j = 0; j < 6; ++j) v[j] = state.q[static_cast<std::size_t>(j)];
    return v;
  }
};

TEST(PumaLinkEmulator, RefusesCommandsBeyondTheLimitsAndHoldsUntilReset) {
  ControllerEmulator controller(lockstep_options());
  Host host(controller);
  robot::link::Command query;
  query.query = true;
  ASSERT_TRUE(host.command(query));
  EXPECT_EQ(host.state.status, robot::link::Status::kHolding);
  const Vector6d start = host.q();
  ASSERT_TRUE(host.command(host.at(start)));
  EXPECT_EQ(host.state.status, robot::link::Status::kOk);

  Vector6d beyond = start;
  beyond[2] = model().limits().upper[2] + 0.01;  // joint 3 past its limit
  ASSERT_TRUE(host.command(host.at(beyond)));
  EXPECT_EQ(host.state.status, robot::link::Status::kFault);
  EXPECT_EQ(host.state.fault, robot::link::Fault::kJointLimit);
  Vector6d jump = start;
  jump[0] += 0.2;  // within the limits, but no arm moves 0.2 rad in 1 ms
  for (int i = 0; i < 200; ++i) ASSERT_TRUE(host.command(host.at(jump)));
  EXPECT_EQ(host.state.status, robot::link::Status::kFault) << "latched";
  EXPECT_LT((controller.true_q() - start).cwiseAbs().maxCoeff(), 2e-3) << "the arm held";

  robot::link::Command reset = host.at(start);
  reset.reset_fault = true;
  ASSERT_TRUE(host.command(reset));
  EXPECT_EQ(host.state.status, robot::link::Status::kOk);
  ASSERT_TRUE(host.command(host.at(jump)));
  EXPECT_EQ(host.state.fault, robot::link::Fault::kBadCommand);
  EXPECT_EQ(controller.counters().rejected, 2u);
}

// Datagrams with chosen sequence numbers and damage, from one socket.
struct RawHost {
  int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  explicit RawHost(std::uint16_t port) {
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    timeval tv{0, 200'000};  // answers come within microseconds; 200 ms means none
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~RawHost() { ::close(fd); }
  void send(const std::uint8_t* data, std::size_t size) {
    ::sendto(fd, data, size, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  }
  // True when a state answering `ack` arrives.
  bool answered(std::uint32_t ack) {
    std::uint8_t buffer[512];
    robot::link::State st;
    for (;;) {
      const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
      if (n <= 0) return false;
      if (robot::link::decode(buffer, static_cast<std::size_t>(n), st) == robot::link::DecodeError::kNone &&
          st.ack == ack)
        return true;
    }
  }
};

TEST(PumaLinkEmulator, DropsDamagedAndStaleDatagrams) {
  ControllerEmulator controller(lockstep_options());
  RawHost host(controller.port());
  robot::link::Command c;
  c.query = true;
  c.sequence = 5;
  const auto five = robot::link::encode(c);
  host.send(five.data(), five.size());
  EXPECT_TRUE(host.answered(5));
  host.send(five.data(), five.size());  // a duplicate
  c.sequence = 4;
  const auto four = robot::link::encode(c);
  host.send(four.data(), four.size());  // late
  auto damaged = five;
  damaged[30] ^= 0x10;  // one bit flipped in transit
  host.send(damaged.data(), damaged.size());
  host.send(five.data(), 20);  // cut short
  EXPECT_FALSE(host.answered(4));
  c.sequence = 6;
  const auto six = robot::link::encode(c);
  host.send(six.data(), six.size());
  EXPECT_TRUE(host.answered(6));
  EXPECT_EQ(controller.counters().dropped_stale, 2u);
  EXPECT_EQ(controller.counters().dropped_damaged, 2u);
  EXPECT_EQ(controller.counters().queries, 2u);
}

TEST(PumaLinkEmulator, InRealTimeItHoldsWhenCommandsStop) {
  ControllerEmulator::Options o = lockstep_options();
  o.lockstep = false;
  ControllerEmulator controller(o);
  Host host(controller);
  robot::link::Command query;
  query.query = true;
  ASSERT_TRUE(host.command(query));
  // Command a slow move for a while, then fall silent: within a bounded (wall) time the controller
  // reports the command timeout and holds.
  Vector6d q = host.q();
  for (int i = 0; i < 50; ++i) {
    q[0] += 1e-4;
    robot::link::Command c = host.at(q);
    c.qd[0] = 0.1;
    host.client.send(c);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  robot::link::State s;
  bool held = false;
  for (int i = 0; i < 400 && !held; ++i) {  // up to 2 s of wall time on a loaded machine
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    while (host.client.poll_newest(s)) {
    }
    held = s.status == robot::link::Status::kHolding && s.fault == robot::link::Fault::kCommandTimeout;
  }
  EXPECT_TRUE(held);
  EXPECT_GE(controller.counters().timeouts, 1u);
}

}  // namespace
}  // namespace wysiwyf::test
