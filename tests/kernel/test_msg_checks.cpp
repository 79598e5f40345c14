// The checks beside the message types (wysiwyf/msg_checks.hpp) and Component::take_checked: a
// sample with a NaN, or an orientation that is no rotation, is refused with why; a good one is
// taken; a LOST hand or a release carries nothing to check; a number beyond any lab's magnitude
// is refused as a NaN is.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

msg::PoseStamped pose(double w) {
  msg::PoseStamped m;
  m.pose().orientation().w(w);
  return m;
}

TEST(MessageChecks, APoseNeedsFiniteNumbersAndARotation) {
  EXPECT_EQ(msg::problem(pose(1)), "");
  EXPECT_EQ(msg::problem(pose(1.005)), "") << "a quaternion a little off unit length is still a rotation";
  EXPECT_NE(msg::problem(pose(0)).find("quaternion of length 0"), std::string::npos) << msg::problem(pose(0));
  EXPECT_NE(msg::problem(pose(2)).find("expected 1"), std::string::npos);
  msg::PoseStamped nan = pose(1);
  nan.pose().position().y(kNan);
  EXPECT_EQ(msg::problem(nan), "a non-finite pose");
}

TEST(MessageChecks, EachTypeChecksWhatItCarries) {
  msg::WrenchStamped w;
  EXPECT_EQ(msg::problem(w), "");
  w.wrench().torque().z(std::numeric_limits<double>::infinity());
  EXPECT_EQ(msg::problem(w), "a non-finite force or torque");

  msg::JointState j;
  EXPECT_EQ(msg::problem(j), "no joint positions");
  j.position() = {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6};  // an arm of 7 joints
  EXPECT_EQ(msg::problem(j), "") << "velocities and efforts may be left out";
  j.velocity().assign(7, 0.0);
  j.velocity()[2] = kNan;  // unknown velocities are allowed
  EXPECT_EQ(msg::problem(j), "");
  j.effort().assign(6, 0.0);
  EXPECT_EQ(msg::problem(j), "6 efforts for 7 joints");
  j.effort().clear();
  j.velocity().resize(8, 0.0);
  EXPECT_EQ(msg::problem(j), "8 velocities for 7 joints");
  j.velocity().resize(7);
  j.position()[5] = kNan;
  EXPECT_EQ(msg::problem(j), "a non-finite joint position");

  msg::HandPosition h;
  h.position().x(kNan);
  h.status(msg::TRACKING_LOST);
  EXPECT_EQ(msg::problem(h), "") << "a lost hand carries no position";
  h.status(msg::TRACKING_OK);
  EXPECT_EQ(msg::problem(h), "a non-finite position");

  msg::CartesianSetpoint s;
  s.pose().orientation().w(1);
  EXPECT_EQ(msg::problem(s), "");
  s.twist().angular().x(kNan);
  EXPECT_EQ(msg::problem(s), "a non-finite twist");

  msg::ObjectState o;
  EXPECT_NE(msg::problem(o), "") << "a zero quaternion is no orientation";
  o.pose().orientation().w(1);
  EXPECT_EQ(msg::problem(o), "");

  msg::Attachment a;
  a.attached(false);
  EXPECT_EQ(msg::problem(a), "") << "a release carries no pose";
  a.attached(true);
  EXPECT_NE(msg::problem(a).find("(obj_T_dev)"), std::string::npos);
}

// A finite 1e308 overflows at its first square (a distance, a spring's force): every number a
// sample carries is refused beyond msgs::kMaxMagnitude, as a NaN is.
TEST(MessageChecks, NumbersBeyondAnyLabsMagnitudeAreRefusedLikeANan) {
  msg::PoseStamped p = pose(1);
  p.pose().position().x(1e308);
  EXPECT_EQ(msg::problem(p), "a position beyond 1e4 m (expected finite, within 1e4)");
  p.pose().position().x(-9999);
  EXPECT_EQ(msg::problem(p), "") << "within 1e4 m";
  msg::WrenchStamped w;
  w.wrench().torque().z(-2e4);
  EXPECT_NE(msg::problem(w).find("beyond 1e4"), std::string::npos);
  msg::JointState j;
  j.position() = {0, 0, 0, 0, 0, 0};
  j.velocity() = {0, 0, 1e300, 0, 0, 0};
  EXPECT_NE(msg::problem(j).find("beyond 1e4"), std::string::npos);
  j.velocity() = {};
  j.effort() = {0, 0, 0, 0, 0, -1e5};
  EXPECT_NE(msg::problem(j).find("beyond 1e4"), std::string::npos);
  msg::HandPosition h;
  h.status(msg::TRACKING_OK);
  h.position().z(1e308);
  EXPECT_EQ(msg::problem(h), "a position beyond 1e4 m (expected finite, within 1e4)");
  msg::CartesianSetpoint s;
  s.pose().orientation().w(1);
  s.twist().angular().y(1e5);
  EXPECT_EQ(msg::problem(s), "a twist beyond 1e4 m/s or rad/s (expected finite, within 1e4)");
}

}  // namespace
}  // namespace wysiwyf::test
