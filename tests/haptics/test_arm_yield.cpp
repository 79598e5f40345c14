// admittance_sim's lead for the arm's give under the user's push (components/haptics/admittance_sim/arm_yield.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "arm_yield.hpp"

namespace wysiwyf::haptics {

constexpr std::int64_t kMs = 1'000'000;

// An arm whose plate gives `compliance` m/N under the force, led by ArmYield; the object still at
// `object`. Returns the plate's last distance from the object after `ticks` of 1 ms.
double push_on_an_arm(ArmYield& yield, double compliance, const Eigen::Vector3d& force, int ticks) {
  const Eigen::Vector3d object(0.6, 0.0, 0.1);
  Eigen::Vector3d plate = object;
  for (int i = 1; i <= ticks; ++i) {
    yield.object_at(i * kMs, object);
    plate = object + yield.lead(force) + compliance * force;  // sent ahead by the lead, given way by c F
    yield.measured(i * kMs, plate, force, 1e-3);
  }
  return (plate - object).norm();
}

TEST(ArmYield, LearnsTheArmsComplianceWhileTheUserPushesAndLeadsTheSetpointByIt) {
  ArmYield yield(5.0, 1e-3, 1.0);
  const Eigen::Vector3d force(-3.0, 0.0, 0.0);
  EXPECT_NEAR(push_on_an_arm(yield, 8e-5, force, 1), 3 * 8e-5, 1e-9) << "at first nothing is led";
  push_on_an_arm(yield, 8e-5, force, 2000);  // 2 s: 10 time constants of 1/5 s
  EXPECT_NEAR(yield.compliance(), 8e-5, 1e-8);
  EXPECT_LE((yield.lead(force) - Eigen::Vector3d(3 * 8e-5, 0, 0)).norm(), 3e-8) << "the setpoint goes against the push";
  EXPECT_LE(push_on_an_arm(yield, 8e-5, 2.5 * force, 1), 1e-7) << "a harder push is led as much harder at once";
}

TEST(ArmYield, LearnsNothingFromALightTouchAStillArmOrABadSample) {
  ArmYield yield(5.0, 1e-3, 1.0);
  push_on_an_arm(yield, 8e-5, Eigen::Vector3d(0.5, 0, 0), 1000);
  EXPECT_EQ(yield.compliance(), 0.0) << "below min_force";
  ArmYield off(0.0, 1e-3, 1.0);
  push_on_an_arm(off, 8e-5, Eigen::Vector3d(5, 0, 0), 1000);
  EXPECT_EQ(off.compliance(), 0.0) << "rate 0: not learned";
  const Eigen::Vector3d nan(std::nan(""), 0, 0);
  yield.object_at(1 * kMs, Eigen::Vector3d::Zero());
  yield.measured(1 * kMs, nan, Eigen::Vector3d(5, 0, 0), 1e-3);
  yield.measured(1 * kMs, Eigen::Vector3d::Zero(), nan, 1e-3);
  EXPECT_EQ(yield.compliance(), 0.0);
  yield.measured(0, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(5, 0, 0), 1e-3);  // older than every object pose kept
  EXPECT_EQ(yield.compliance(), 0.0);
}

TEST(ArmYield, StaysWithinItsBoundsWhateverThePlateDoes) {
  ArmYield yield(50.0, 1e-3, 1.0);
  push_on_an_arm(yield, 0.5, Eigen::Vector3d(2, 0, 0), 1000);  // a plate that gives 0.5 m/N
  EXPECT_EQ(yield.compliance(), 1e-3);
  push_on_an_arm(yield, -0.5, Eigen::Vector3d(2, 0, 0), 1000);  // one that pushes back
  EXPECT_EQ(yield.compliance(), 0.0);
}

}  // namespace wysiwyf::haptics
