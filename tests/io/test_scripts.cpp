// The scripted sources: setpoint_script and wrench_script, each run alone in a Harness.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

constexpr std::int64_t kMs = 1'000'000;

Eigen::Vector3d position(const msg::CartesianSetpoint& s) {
  return {s.pose().position().x(), s.pose().position().y(), s.pose().position().z()};
}
Eigen::Quaterniond orientation(const msg::CartesianSetpoint& s) {
  const auto& q = s.pose().orientation();
  return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
}

TEST(SetpointScript, PassesThroughEachWaypointAtItsTimeAndHoldsAfterTheLast) {
  Harness h("setpoint_script",
            "{waypoints: [0, 0.5, 0, 0.3, 0, 0, 0,  1, 0.6, 0.1, 0.3, 0, 0, 1.5,  3, 0.6, 0.1, 0.5, 0.3, 0, 1.5]}");
  auto out = h.watch<msg::CartesianSetpoint>("setpoint");
  h.activate();
  msg::CartesianSetpoint s;
  for (std::int64_t t : {0 * kMs, 1000 * kMs, 3000 * kMs, 5000 * kMs}) {
    h.tick(Time{t});
    ASSERT_TRUE(out.take_latest(s));
  }
  // The last two: at and after the final waypoint.
  EXPECT_NEAR((position(s) - Eigen::Vector3d(0.6, 0.1, 0.5)).norm(), 0, 1e-12);
  const Eigen::Quaterniond expected =
      Eigen::AngleAxisd(1.5, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX());
  EXPECT_NEAR(orientation(s).angularDistance(expected), 0, 1e-12);
  EXPECT_EQ(s.twist().linear().z(), 0.0);
  EXPECT_EQ(std::string(s.header().frame_id().c_str()), "base");
  EXPECT_EQ(std::string(s.source().c_str()), "script");
}

TEST(SetpointScript, TwistIsTheDerivativeOfThePoseAndVelocityIsContinuous) {
  Harness h("setpoint_script",
            "{waypoints: [0, 0.5, 0, 0.3, 0, 0, 0,  1, 0.6, 0.1, 0.3, 0.4, -0.2, 1.0,  2.5, 0.4, 0.2, 0.45, 0, 0, 0]}");
  auto out = h.watch<msg::CartesianSetpoint>("setpoint");
  h.activate();
  std::vector<msg::CartesianSetpoint> samples;
  for (std::int64_t t = 0; t <= 2600 * kMs; t += kMs) {
    h.tick(Time{t});
    samples.emplace_back();
    ASSERT_TRUE(out.take(samples.back()));
  }
  const double dt = 1e-3;
  double worst_linear = 0, worst_angular = 0, worst_jump = 0;
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {
    const Eigen::Vector3d fd = (position(samples[i + 1]) - position(samples[i - 1])) / (2 * dt);
    const auto& l = samples[i].twist().linear();
    worst_linear = std::max(worst_linear, (fd - Eigen::Vector3d(l.x(), l.y(), l.z())).norm());
    const Eigen::AngleAxisd dq(orientation(samples[i + 1]) * orientation(samples[i - 1]).inverse());
    const Eigen::Vector3d w_fd = dq.angle() * dq.axis() / (2 * dt);
    const auto& a = samples[i].twist().angular();
    worst_angular = std::max(worst_angular, (w_fd - Eigen::Vector3d(a.x(), a.y(), a.z())).norm());
    const auto& prev = samples[i - 1].twist().linear();
    worst_jump = std::max(
        worst_jump, (Eigen::Vector3d(l.x(), l.y(), l.z()) - Eigen::Vector3d(prev.x(), prev.y(), prev.z())).norm());
  }
  EXPECT_LT(worst_linear, 1e-5);  // central difference error of a quintic at 1 ms
  EXPECT_LT(worst_angular, 1e-4);
  EXPECT_LT(worst_jump, 1e-3);  // no step in velocity from one ms to the next (peak accel < 1 m/s^2)
}

TEST(SetpointScript, LoopsWhenAsked) {
  Harness h("setpoint_script", "{loop: true, waypoints: [0, 0, 0, 0, 0, 0, 0,  2, 1, 0, 0, 0, 0, 0]}");
  auto out = h.watch<msg::CartesianSetpoint>("setpoint");
  h.activate();
  msg::CartesianSetpoint a, b;
  h.tick(Time{500 * kMs});
  ASSERT_TRUE(out.take(a));
  h.tick(Time{2500 * kMs});
  ASSERT_TRUE(out.take(b));
  EXPECT_NEAR(a.pose().position().x(), b.pose().position().x(), 1e-12);
}

// With start_arm the script starts the arm as the supervisor would: it asks it to
// clear a fault of its input (the stream lost while the script's process was away), starts its
// script once the arm is ready, and never asks again.
TEST(SetpointScript, StartsTheArmOnceAndOnlyAtItsStart) {
  Harness h("setpoint_script", "{start_arm: true, waypoints: [0, 0.5, 0, 0.3, 0, 0, 0,  1, 0.6, 0, 0.3, 0, 0, 0]}",
            1000);
  auto status = h.feed<msg::RobotStatus>("arm_status");
  auto out = h.watch<msg::CartesianSetpoint>("setpoint");
  auto requests = h.watch<msg::ArmRequest>("arm_request");
  h.activate();
  const auto count = [](auto& in, auto sample) {
    int n = 0;
    while (in.take(sample)) ++n;
    return n;
  };
  msg::CartesianSetpoint sp;
  msg::ArmRequest rq;
  for (int t = 0; t < 50; ++t) h.tick(Time{t * kMs});  // no status yet: it waits, writes nothing, says why
  EXPECT_EQ(count(out, sp), 0);
  EXPECT_EQ(count(requests, rq), 0);
  EXPECT_NE(h.health_reason().find("waiting for the arm's status"), std::string::npos) << h.health_reason();
  msg::RobotStatus lost;
  lost.state(msg::ARM_FAULT);
  lost.clearable(true);
  lost.reason("setpoint stream lost: no setpoint for 31 ms from 'script'");
  status.write(lost);
  for (int t = 50; t < 300; ++t) h.tick(Time{t * kMs});
  EXPECT_EQ(count(out, sp), 0) << "no setpoint to an arm that holds";
  EXPECT_EQ(count(requests, rq), 3) << "asked at 50, 150 and 250 ms";
  EXPECT_EQ(rq.request(), msg::ARM_CLEAR_INPUT_FAULT);
  msg::RobotStatus ready;
  ready.state(msg::ARM_HOLDING);
  ready.reason("input fault cleared; waiting for a setpoint");
  status.write(ready);
  h.tick(Time{300 * kMs});
  ASSERT_TRUE(out.take_latest(sp));
  EXPECT_NEAR(position(sp).x(), 0.5, 1e-12) << "the script starts at its first waypoint";
  status.write(lost);  // lost again later: not this script's start, never cleared by it
  for (int t = 301; t < 1000; ++t) h.tick(Time{t * kMs});
  EXPECT_EQ(count(requests, rq), 0);
  EXPECT_EQ(count(out, sp), 699) << "it went on writing";
}

TEST(SetpointScript, RejectsBadWaypointsWithAClearMessage) {
  try {
    Harness h("setpoint_script", "{waypoints: [0, 1, 2, 3, 0, 0, 0,  0, 1, 2, 3, 0, 0, 0]}");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("expected strictly increasing times"), std::string::npos) << e.what();
  }
  try {
    Harness h("setpoint_script", "{waypoints: [0, 1, 2]}");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    // (the kernel checks the list's shape, at the value's line)
    EXPECT_NE(std::string(e.what()).find(":8:25: error: parameter 'waypoints' of component 'dut' (setpoint_script): "
                                         "found 3 values; expected whole rows of 7 values"),
              std::string::npos)
        << e.what();
  }
}

TEST(WrenchScript, InterpolatesLinearlyBetweenKeyframes) {
  Harness h("wrench_script", "{keyframes: [0, 0, 0, 0, 0, 0, 0,  1, 0, 0, -10, 0, 0, 0,  2, 4, 0, -10, 0, 0.5, 0]}");
  auto out = h.watch<msg::WrenchStamped>("wrench");
  h.activate();
  msg::WrenchStamped w;
  h.tick(Time{0});  // the script's time starts at the first tick
  ASSERT_TRUE(out.take(w));
  EXPECT_DOUBLE_EQ(w.wrench().force().z(), 0.0);
  h.tick(Time{250 * kMs});
  ASSERT_TRUE(out.take(w));
  EXPECT_DOUBLE_EQ(w.wrench().force().z(), -2.5);
  h.tick(Time{1500 * kMs});
  ASSERT_TRUE(out.take(w));
  EXPECT_DOUBLE_EQ(w.wrench().force().x(), 2.0);
  EXPECT_DOUBLE_EQ(w.wrench().torque().y(), 0.25);
  h.tick(Time{9000 * kMs});
  ASSERT_TRUE(out.take(w));
  EXPECT_DOUBLE_EQ(w.wrench().force().x(), 4.0);
  EXPECT_EQ(w.header().seq(), 3u);
  EXPECT_EQ(std::string(w.header().frame_id().c_str()), "sensor");
}

}  // namespace wysiwyf::test

namespace wysiwyf::test {

TEST(WrenchLowpass, FollowsTheExactFirstOrderStepResponse) {
  Harness h("wrench_lowpass", "{cutoff_hz: 10}", 1000);
  auto raw = h.feed<msg::WrenchStamped>("raw");
  auto filtered = h.watch<msg::WrenchStamped>("filtered");
  h.activate();
  msg::WrenchStamped w;
  for (int i = 0; i <= 100; ++i) {
    w.header().stamp_ns(i * kMs);
    w.wrench().force().x(i == 0 ? 0.0 : 5.0);  // a step after the first sample
    w.wrench().torque().z(i == 0 ? 0.0 : -1.0);
    raw.write(w);
    h.tick(Time{i * kMs});
  }
  ASSERT_TRUE(filtered.take_latest(w));
  // Each sample counts as the input over the interval that ends at its stamp, so 100 updates
  // after the 0 sample cover 100 ms of the step.
  const double expected = 5.0 * (1.0 - std::exp(-2 * M_PI * 10 * 0.100));
  EXPECT_NEAR(w.wrench().force().x(), expected, 1e-9);
  EXPECT_NEAR(w.wrench().torque().z(), -expected / 5.0, 1e-9);
  EXPECT_EQ(w.header().stamp_ns(), 100 * kMs);
}

}  // namespace wysiwyf::test
