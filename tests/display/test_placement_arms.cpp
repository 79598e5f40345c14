// placement's path_reachable on the arms besides the PUMA 560 (the UR5e's closed-form IK, the
// FR3's numerical one): a plate pose in front of the arm near (0.7, 0, 0.1), its face towards +x,
// is reached along a planned path from 8 cm behind it, on one IK branch within the joint limits;
// and a pose 2 m away is reported unreachable with why.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "arm_model/arm_model.hpp"
#include "placement.hpp"

namespace wysiwyf::display {
namespace {

std::string urdf(const char* arm) { return std::string(WYSIWYF_CONFIG_DIR) + "/robots/" + arm + ".urdf"; }

// The plate at `position`, its face (dev z) towards +x.
Eigen::Isometry3d facing_x(const Eigen::Vector3d& position) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T.translation() = position;
  return T;
}

// Joints with the plate at base_T_dev, from the middle of the joint ranges (or why not).
robot::ArmIkResult posture(const robot::ArmModel& arm, const Eigen::Isometry3d& base_T_dev) {
  const robot::JointVector middle = 0.5 * (arm.limits().lower.cwiseMax(-M_PI) + arm.limits().upper.cwiseMin(M_PI));
  return arm.ik_nearest(base_T_dev, middle);
}

class PlacementOn : public ::testing::TestWithParam<const char*> {};

TEST_P(PlacementOn, APlatePoseInFrontOfTheArmFacingXIsReachable) {
  const robot::ArmModel arm(urdf(GetParam()), "dev");
  const Eigen::Isometry3d target = facing_x({0.7, 0.0, 0.1});
  const Eigen::Isometry3d start = facing_x({0.62, 0.0, 0.1});
  const robot::ArmIkResult at_start = posture(arm, start);
  ASSERT_TRUE(at_start.ok()) << GetParam() << ": no posture 8 cm behind the target: " << to_string(at_start.status);
  PlatePath path;
  path.plan(start, {}, target);
  robot::JointVector q_end;
  const std::string why = path_reachable(arm, path, at_start.q, q_end);
  EXPECT_EQ(why, "") << GetParam();
  ASSERT_EQ(q_end.size(), arm.dof());
  EXPECT_TRUE(arm.limits().within(q_end, 1e-9));
  const Eigen::Isometry3d reached = arm.fk(q_end);
  EXPECT_LT((reached.translation() - target.translation()).norm(), 1e-6) << GetParam();
  EXPECT_LT(Eigen::AngleAxisd(reached.linear().transpose() * target.linear()).angle(), 1e-6) << GetParam();
}

TEST_P(PlacementOn, APoseOutOfReachIsReportedWithWhy) {
  const robot::ArmModel arm(urdf(GetParam()), "dev");
  const Eigen::Isometry3d start = facing_x({0.62, 0.0, 0.1});
  const robot::ArmIkResult at_start = posture(arm, start);
  ASSERT_TRUE(at_start.ok()) << GetParam();
  PlatePath path;
  path.plan(start, {}, facing_x({2.0, 0.0, 0.1}));
  robot::JointVector q_end;
  const std::string why = path_reachable(arm, path, at_start.q, q_end);
  EXPECT_FALSE(why.empty()) << GetParam() << ": a plate 2 m out reported reachable";
  std::printf("[ reason   ] %s: %s\n", GetParam(), why.c_str());
}

INSTANTIATE_TEST_SUITE_P(Arms, PlacementOn, ::testing::Values("ur5e", "fr3"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

}  // namespace
}  // namespace wysiwyf::display
