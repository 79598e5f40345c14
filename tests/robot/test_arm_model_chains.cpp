// ArmModel on chains other than the three arms' and checks independent of KDL: a chain with a
// prismatic and a continuous joint against its hand-written FK, the geometric Jacobian of every
// arm against central differences of FK, and a UR5e wrist singularity in the closed form.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "arm_model_test_util.hpp"

namespace wysiwyf::robot {
namespace {

using test::kFr3Urdf;
using test::kPumaUrdf;
using test::kUr5eUrdf;

// The Jacobian [v; w] by central differences of fk: v from the origin, w from R(q + h) R(q - h)^T.
ArmJacobian numerical_jacobian(const ArmModel& arm, const JointVector& q, FrameId f, double h = 1e-6) {
  ArmJacobian J(6, arm.dof());
  for (int j = 0; j < arm.dof(); ++j) {
    JointVector qp = q, qm = q;
    qp[j] += h;
    qm[j] -= h;
    const Eigen::Isometry3d Tp = arm.fk(qp, f), Tm = arm.fk(qm, f);
    J.block<3, 1>(0, j) = (Tp.translation() - Tm.translation()) / (2.0 * h);
    const Eigen::AngleAxisd turn(Eigen::Matrix3d(Tp.linear() * Tm.linear().transpose()));
    J.block<3, 1>(3, j) = turn.angle() * turn.axis() / (2.0 * h);
  }
  return J;
}

TEST(ArmModelChains, JacobianIsTheDerivativeOfFkOnEveryArm) {
  for (const std::string& path : {kPumaUrdf, kUr5eUrdf, kFr3Urdf}) {
    const ArmModel arm(path);
    std::mt19937_64 rng(81);
    double worst = 0.0;
    for (int n = 0; n < 50; ++n) {
      const JointVector q = test::random_q(arm, rng);
      for (const std::string& name : arm.frame_names()) {
        const FrameId f = arm.frame(name);
        worst = std::max(worst, (arm.jacobian(q, f) - numerical_jacobian(arm, q, f)).cwiseAbs().maxCoeff());
      }
    }
    EXPECT_LT(worst, 1e-7) << path;
    std::printf("%s: worst |J - central differences of FK| %.2e\n", path.c_str(), worst);
  }
}

// base -> slide (prismatic, x) -> carriage -> turn (revolute, z, 0.2 up) -> arm1 -> spin
// (continuous, y, 0.3 along x) -> arm2 -> flange (fixed, 0.25 along x).
class ArmModelChainsSlide : public ::testing::Test {
 protected:
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("arm_model_slide_" + std::to_string(::getpid()) + ".urdf");
  void SetUp() override {
    const char* inertial =
        "<inertial><origin xyz='0.1 0.02 -0.01'/><mass value='2'/><inertia ixx='0.02' "
        "ixy='0.001' ixz='0' iyy='0.03' iyz='0.002' izz='0.04'/></inertial>";
    std::ofstream(path) << "<robot name='slide'><link name='base_link'/><link name='carriage'>" << inertial
                        << "</link><link name='arm1'>" << inertial << "</link><link name='arm2'>" << inertial
                        << "</link><link name='flange'/>"
                           "<joint name='slide' type='prismatic'><parent link='base_link'/><child link='carriage'/>"
                           "<axis xyz='1 0 0'/><limit lower='-0.5' upper='0.5' velocity='1' effort='100'/></joint>"
                           "<joint name='turn' type='revolute'><parent link='carriage'/><child link='arm1'/>"
                           "<origin xyz='0 0 0.2'/><axis xyz='0 0 1'/>"
                           "<limit lower='-2' upper='2' velocity='1' effort='10'/></joint>"
                           "<joint name='spin' type='continuous'><parent link='arm1'/><child link='arm2'/>"
                           "<origin xyz='0.3 0 0'/><axis xyz='0 1 0'/><limit velocity='2' effort='5'/></joint>"
                           "<joint name='tool' type='fixed'><parent link='arm2'/><child link='flange'/>"
                           "<origin xyz='0.25 0 0'/></joint></robot>";
  }
  void TearDown() override { std::filesystem::remove(path); }

  static Eigen::Isometry3d expected_fk(const JointVector& q) {
    return test::translation(q[0], 0, 0.2) * Eigen::AngleAxisd(q[1], Eigen::Vector3d::UnitZ()) *
           test::translation(0.3, 0, 0) * Eigen::AngleAxisd(q[2], Eigen::Vector3d::UnitY()) *
           test::translation(0.25, 0, 0);
  }
};

TEST_F(ArmModelChainsSlide, PrismaticAndContinuousJointsWork) {
  const ArmModel arm(path.string());
  ASSERT_EQ(arm.dof(), 3);
  EXPECT_EQ(arm.joint_kind(0), JointKind::kPrismatic);
  EXPECT_EQ(arm.joint_kind(1), JointKind::kRevolute);
  EXPECT_EQ(arm.joint_kind(2), JointKind::kContinuous);
  EXPECT_TRUE(std::isinf(arm.limits().upper[2]) && std::isinf(arm.limits().lower[2]));
  EXPECT_EQ(arm.limits().effort[2], 5.0);
  EXPECT_EQ(arm.ik_method(), ArmIkMethod::kNumerical);
  std::mt19937_64 rng(82);
  for (int n = 0; n < 200; ++n) {
    JointVector q(3);
    q << std::uniform_real_distribution<double>(-0.5, 0.5)(rng), std::uniform_real_distribution<double>(-2, 2)(rng),
        std::uniform_real_distribution<double>(-7, 7)(rng);
    EXPECT_LT((arm.fk(q).matrix() - expected_fk(q).matrix()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((arm.jacobian(q) - numerical_jacobian(arm, q, arm.tip())).cwiseAbs().maxCoeff(), 1e-7);
    const JointVector qd = test::random_vector(3, 1.0, rng), qdd = test::random_vector(3, 1.0, rng);
    const JointVector tau = arm.rnea(q, qd, qdd);
    EXPECT_LT((tau - (arm.mass_matrix(q) * qdd + arm.coriolis(q, qd) + arm.gravity_torques(q))).cwiseAbs().maxCoeff(),
              1e-9);
    EXPECT_LT((arm.forward_dynamics(q, qd, tau) - qdd).cwiseAbs().maxCoeff(), 1e-9);
    // The slide carries all three bodies: its force against gravity along x is zero.
    EXPECT_NEAR(arm.gravity_torques(q)[0], 0.0, 1e-12);
    EXPECT_NEAR(arm.gravity_torques(q, Eigen::Vector3d(-9.81, 0, 0))[0], 6 * 9.81, 1e-9);
    // IK from nearby joints returns the joints, the continuous angle on q_ref's side of 2 pi.
    if (std::abs(q[1]) < 1.9) {
      const ArmIkResult r = arm.ik_nearest(arm.fk(q), q + test::random_vector(3, 0.05, rng));
      ASSERT_TRUE(r.ok()) << to_string(r.status);
      EXPECT_LT((r.q - q).cwiseAbs().maxCoeff(), 1e-6);
    }
  }
}

// At theta5 = 0 the UR's axes 4 and 6 line up: only theta4 + theta6 is determined. The closed
// form keeps theta6 at q_ref's, flags the solution, and still reaches the pose.
TEST(ArmModelChains, Ur5eWristSingularityKeepsTheReferenceAngle) {
  const ArmModel arm(kUr5eUrdf);
  JointVector q(6);
  q << 0.3, -1.2, 1.4, -0.5, 0.0, 0.7;
  const ArmIkSolutions all = arm.ik(arm.fk(q), q);
  ASSERT_EQ(all.status, ArmIkStatus::kOk);
  bool found = false;
  for (int k = 0; k < all.count; ++k) {
    const ArmIkSolution& s = all.solution[static_cast<std::size_t>(k)];
    EXPECT_LT(test::position_error(arm.fk(s.q), arm.fk(q)), 1e-12);
    EXPECT_LT(test::rotation_error(arm.fk(s.q), arm.fk(q)), 1e-12);
    if (test::angle_distance(s.q, q) < 1e-9) {
      found = true;
      EXPECT_TRUE(s.singular);
    }
  }
  EXPECT_TRUE(found);
  const ArmIkResult r = arm.ik_nearest(arm.fk(q), q);
  ASSERT_TRUE(r.ok());
  EXPECT_LT((r.q - q).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_TRUE(r.singular);
}

}  // namespace
}  // namespace wysiwyf::robot
