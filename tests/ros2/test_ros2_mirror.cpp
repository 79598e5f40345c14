// ros2_mirror alone (the Harness): ROS 2's types filled from WYSIWYF's, stamps converted exactly,
// a stamp ROS 2 cannot hold refused, the ports an instance has chosen by `mirror`.
#include <gtest/gtest.h>

#include <cmath>

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"
#include "wysiwyf_ros2_msgs/messages.hpp"

using namespace wysiwyf;
// (WYSIWYF has modules geometry_msgs and std_msgs of its own: ROS 2's by these names)
namespace ros2_sensor = ::sensor_msgs::msg::dds_;
namespace ros2_geometry = ::geometry_msgs::msg::dds_;

namespace {

constexpr std::int64_t kMs = 1'000'000;

// The ROS 2 stamp a WYSIWYF stamp becomes, through the component.
bool mirrored_stamp(std::int64_t ns, std::int32_t& sec, std::uint32_t& nanosec, std::uint64_t& rejected) {
  Harness h("ros2_mirror", "{mirror: [wrench]}");
  auto in = h.feed<msg::WrenchStamped>("wrench");
  auto out = h.watch<ros2_geometry::WrenchStamped_>("ros2_wrench");
  h.activate();
  msg::WrenchStamped w;
  w.header().stamp_ns(ns);
  in.write(w);
  h.tick(Time{kMs});
  rejected = h.rejected("wrench");
  ros2_geometry::WrenchStamped_ r;
  if (!out.take(r)) return false;
  sec = r.header().stamp().sec();
  nanosec = r.header().stamp().nanosec();
  return true;
}

bool has_port(const Harness& h, const std::string& name) {
  for (const auto& p : h.description().ports)
    if (p.name == name) return true;
  return false;
}

}  // namespace

TEST(Ros2Mirror, JointStateAsSensorMsgsWithNamesStampAndFrame) {
  Harness h("ros2_mirror", "{joint_names: [a, b, c, d, e, f]}");
  auto in = h.feed<msg::JointState>("joint_state");
  auto out = h.watch<ros2_sensor::JointState_>("ros2_joint_state");
  h.activate();
  msg::JointState js;
  fill_header(js.header(), 1'700'000'000'123'456'789, 41, "base");
  js.position().resize(6), js.velocity().resize(6), js.effort().resize(6);
  for (std::size_t j = 0; j < 6; ++j) {
    js.position()[j] = 0.1 * static_cast<double>(j) + 1e-17;
    js.velocity()[j] = -static_cast<double>(j);
    js.effort()[j] = 1e300 * static_cast<double>(j);
  }
  in.write(js);
  js.header().stamp_ns(js.header().stamp_ns() + kMs);
  in.write(js);  // two in one tick: both mirrored
  h.tick(Time{kMs});
  ros2_sensor::JointState_ r;
  ASSERT_TRUE(out.take(r));
  EXPECT_EQ(r.header().stamp().sec(), 1'700'000'000);
  EXPECT_EQ(r.header().stamp().nanosec(), 123'456'789u);
  EXPECT_EQ(r.header().frame_id(), "base");
  EXPECT_EQ(r.name(), (std::vector<std::string>{"a", "b", "c", "d", "e", "f"}));
  ASSERT_EQ(r.position().size(), 6u);
  ASSERT_EQ(r.velocity().size(), 6u);
  ASSERT_EQ(r.effort().size(), 6u);
  for (std::size_t j = 0; j < 6; ++j) {
    EXPECT_EQ(r.position()[j], js.position()[j]);  // bit for bit
    EXPECT_EQ(r.velocity()[j], js.velocity()[j]);
    EXPECT_EQ(r.effort()[j], js.effort()[j]);
  }
  ASSERT_TRUE(out.take(r));
  EXPECT_EQ(r.header().stamp().nanosec(), 124'456'789u);
  EXPECT_FALSE(out.take(r));
}

// A 7-joint arm (the FR3): its names; a source without velocities or efforts gives NaN (ROS 2's
// "unknown"); a joint state of another joint count than the names is refused.
TEST(Ros2Mirror, AnArmOfSevenJointsAndAJointStateOfAnotherCountRefused) {
  Harness h("ros2_mirror", "{joint_names: [j1, j2, j3, j4, j5, j6, j7]}");
  auto in = h.feed<msg::JointState>("joint_state");
  auto out = h.watch<ros2_sensor::JointState_>("ros2_joint_state");
  h.activate();
  msg::JointState js;
  fill_header(js.header(), kMs, 0, "base");
  js.position() = {0.1, 0.2, 0.3, -2.0, 0.5, 1.6, 0.7};
  in.write(js);
  js.position().resize(6);
  in.write(js);
  h.tick(Time{kMs});
  ros2_sensor::JointState_ r;
  ASSERT_TRUE(out.take(r));
  ASSERT_EQ(r.position().size(), 7u);
  EXPECT_EQ(r.position()[6], 0.7);
  EXPECT_TRUE(std::isnan(r.velocity()[6]));
  EXPECT_TRUE(std::isnan(r.effort()[0]));
  EXPECT_FALSE(out.take(r)) << "the 6-joint state is refused";
  EXPECT_EQ(h.rejected("joint_state"), 1u);
}

TEST(Ros2Mirror, WrenchAndPoseKeepEveryValueAndTheFrame) {
  Harness h("ros2_mirror");
  auto wrench_in = h.feed<msg::WrenchStamped>("wrench");
  auto pose_in = h.feed<msg::PoseStamped>("pose");
  auto wrench_out = h.watch<ros2_geometry::WrenchStamped_>("ros2_wrench");
  auto pose_out = h.watch<ros2_geometry::PoseStamped_>("ros2_pose");
  h.activate();
  msg::WrenchStamped w;
  fill_header(w.header(), 2500 * kMs, 0, "ft_sensor");
  w.wrench().force().x(-11.343), w.wrench().force().y(0.25), w.wrench().force().z(-0.5);
  w.wrench().torque().x(1e-9), w.wrench().torque().y(-0.18887), w.wrench().torque().z(3);
  wrench_in.write(w);
  msg::PoseStamped p;
  fill_header(p.header(), 2500 * kMs, 0, "base");
  p.child_frame_id("dev");
  p.pose().position().x(0.7), p.pose().position().y(-0.05), p.pose().position().z(0.25);
  p.pose().orientation().x(0.1), p.pose().orientation().y(0.2), p.pose().orientation().z(0.3);
  p.pose().orientation().w(0.9);
  pose_in.write(p);
  h.tick(Time{2500 * kMs});

  ros2_geometry::WrenchStamped_ rw;
  ASSERT_TRUE(wrench_out.take(rw));
  EXPECT_EQ(rw.header().stamp().sec(), 2);
  EXPECT_EQ(rw.header().stamp().nanosec(), 500'000'000u);
  EXPECT_EQ(rw.header().frame_id(), "ft_sensor");
  EXPECT_EQ(rw.wrench().force().x(), -11.343);
  EXPECT_EQ(rw.wrench().force().y(), 0.25);
  EXPECT_EQ(rw.wrench().force().z(), -0.5);
  EXPECT_EQ(rw.wrench().torque().x(), 1e-9);
  EXPECT_EQ(rw.wrench().torque().y(), -0.18887);
  EXPECT_EQ(rw.wrench().torque().z(), 3.0);

  ros2_geometry::PoseStamped_ rp;
  ASSERT_TRUE(pose_out.take(rp));
  EXPECT_EQ(rp.header().frame_id(), "base");
  EXPECT_EQ(rp.pose().position().x(), 0.7);
  EXPECT_EQ(rp.pose().position().y(), -0.05);
  EXPECT_EQ(rp.pose().position().z(), 0.25);
  EXPECT_EQ(rp.pose().orientation().x(), 0.1);
  EXPECT_EQ(rp.pose().orientation().y(), 0.2);
  EXPECT_EQ(rp.pose().orientation().z(), 0.3);
  EXPECT_EQ(rp.pose().orientation().w(), 0.9);
}

TEST(Ros2Mirror, StampsBecomeSecondsFlooredAndNanosecondsInRange) {
  struct Case {
    std::int64_t ns;
    std::int32_t sec;
    std::uint32_t nanosec;
  };
  constexpr std::int64_t kS = 1'000'000'000;
  constexpr std::int64_t kMaxSec = std::numeric_limits<std::int32_t>::max();
  constexpr std::int64_t kMinSec = std::numeric_limits<std::int32_t>::min();
  const Case cases[] = {
      {0, 0, 0},
      {1, 0, 1},
      {kS - 1, 0, 999'999'999},
      {kS, 1, 0},
      {-1, -1, 999'999'999},
      {-1'700'000'000, -2, 300'000'000},  // ROS 2's own example: -1.7 s
      {-kS, -1, 0},
      {-kS - 1, -2, 999'999'999},
      {kMaxSec * kS + kS - 1, std::numeric_limits<std::int32_t>::max(), 999'999'999},
      {kMinSec * kS, std::numeric_limits<std::int32_t>::min(), 0},
  };
  for (const Case& c : cases) {
    std::int32_t sec = 7;
    std::uint32_t nanosec = 7;
    std::uint64_t rejected = 0;
    ASSERT_TRUE(mirrored_stamp(c.ns, sec, nanosec, rejected)) << c.ns;
    EXPECT_EQ(sec, c.sec) << c.ns;
    EXPECT_EQ(nanosec, c.nanosec) << c.ns;
    EXPECT_EQ(rejected, 0u) << c.ns;
  }
}

TEST(Ros2Mirror, RefusesAStampBeyondInt32Seconds) {
  constexpr std::int64_t kS = 1'000'000'000;
  for (const std::int64_t ns : {(std::int64_t{std::numeric_limits<std::int32_t>::max()} + 1) * kS,
                                std::int64_t{std::numeric_limits<std::int32_t>::min()} * kS - 1,
                                std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()}) {
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
    std::uint64_t rejected = 0;
    EXPECT_FALSE(mirrored_stamp(ns, sec, nanosec, rejected)) << ns << ": mirrored as " << sec << " s";
    EXPECT_EQ(rejected, 1u) << ns;
  }
}

TEST(Ros2Mirror, HasThePortsItsMirrorParameterNamesWithRos2TypeNames) {
  Harness all("ros2_mirror");
  for (const char* port : {"joint_state", "wrench", "pose", "ros2_joint_state", "ros2_wrench", "ros2_pose"})
    EXPECT_TRUE(has_port(all, port)) << port;
  std::map<std::string, std::string> types;
  for (const auto& p : all.description().ports) types[p.name] = p.type_name;
  EXPECT_EQ(types["ros2_joint_state"], "sensor_msgs::msg::dds_::JointState_");
  EXPECT_EQ(types["ros2_wrench"], "geometry_msgs::msg::dds_::WrenchStamped_");
  EXPECT_EQ(types["ros2_pose"], "geometry_msgs::msg::dds_::PoseStamped_");
  Harness poses("ros2_mirror", "{mirror: [pose]}");
  EXPECT_TRUE(has_port(poses, "pose"));
  EXPECT_TRUE(has_port(poses, "ros2_pose"));
  EXPECT_FALSE(has_port(poses, "joint_state"));
  EXPECT_FALSE(has_port(poses, "ros2_wrench"));
}

TEST(Ros2Mirror, RejectsUnknownOrRepeatedStreamsAndAWrongNumberOfJointNames) {
  const std::pair<const char*, const char*> bad[] = {
      {"{mirror: [joints]}", "found 'joints'; expected joint_state, wrench or pose"},
      {"{mirror: [pose, pose]}", "'pose' twice"},
      {"{mirror: []}", "expected at least 1 value"},
      {"{joint_names: [a, b, c, d, e, f, g, h, i]}", "expected 1 to 8 values"},
  };
  for (const auto& [params, expected] : bad) {
    try {
      Harness h("ros2_mirror", params);
      ADD_FAILURE() << params << ": accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << params << ": " << e.what();
    }
  }
}
