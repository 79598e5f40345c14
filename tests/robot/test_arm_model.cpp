// The generic arm model (libs/robot/arm_model) against PumaModel on puma560.urdf (frames, limits,
// bodies, FK at every frame, Jacobian, RNEA, mass matrix, forward dynamics), against the
// published DH tables of the UR5e and the FR3, the dynamics' own identities, gravity against the
// potential energy's gradient, load errors, and no heap allocation in the hot calls.
// (IK: test_arm_model_ik.cpp; collision shapes: test_arm_model_collision.cpp.)
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>
#include <unistd.h>

#include "arm_model_test_util.hpp"
#include "puma_model/puma_model.hpp"

// Every malloc of the process while `g_counting` is set is counted (glibc's own allocator
// underneath): Eigen, KDL and operator new all allocate through it.
extern "C" void* __libc_malloc(std::size_t size);
namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_mallocs{0};
}  // namespace
extern "C" void* malloc(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_mallocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}

namespace wysiwyf::robot {
namespace {

using test::kFr3Urdf;
using test::kPi;
using test::kPumaUrdf;
using test::kUr5eUrdf;

TEST(ArmModelPuma, LoadsTheSameChainFramesLimitsAndBodiesAsPumaModel) {
  const PumaModel puma(kPumaUrdf);
  const ArmModel arm(kPumaUrdf);
  ASSERT_EQ(arm.dof(), 6);
  EXPECT_EQ(arm.ik_method(), ArmIkMethod::kPumaClosedForm);
  EXPECT_EQ(arm.frame_names(), puma.frame_names());
  EXPECT_EQ(arm.frame_name(arm.tip()), "flange");
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(arm.joint_names()[static_cast<std::size_t>(j)], puma.joint_names()[static_cast<std::size_t>(j)]);
    EXPECT_EQ(arm.joint_kind(j), JointKind::kRevolute);
    EXPECT_EQ(arm.limits().lower[j], puma.limits().lower[j]);
    EXPECT_EQ(arm.limits().upper[j], puma.limits().upper[j]);
    EXPECT_EQ(arm.limits().velocity[j], puma.limits().velocity[j]);
    EXPECT_EQ(arm.limits().effort[j], puma.limits().effort[j]);
  }
  for (int k = 0; k <= 6; ++k) {
    EXPECT_NEAR(arm.body(k).mass, puma.body(k).mass, 1e-12) << k;
    EXPECT_LT((arm.body(k).com - puma.body(k).com).norm(), 1e-12) << k;
    EXPECT_LT((arm.body(k).inertia - puma.body(k).inertia).norm(), 1e-12) << k;
  }
  EXPECT_THROW(arm.frame("nope"), std::out_of_range);
  EXPECT_EQ(arm.frame_name(arm.body_frame(0)), "base_link");
  EXPECT_EQ(arm.frame_name(arm.body_frame(6)), "link6");
}

TEST(ArmModelPuma, ForwardKinematicsAndJacobianAtEveryFrameEqualPumaModel) {
  const PumaModel puma(kPumaUrdf);
  const ArmModel arm(kPumaUrdf);
  std::mt19937_64 rng(51);
  double worst_fk = 0.0, worst_jacobian = 0.0;
  for (int n = 0; n < 500; ++n) {
    const JointVector q = test::random_q(arm, rng);
    for (const std::string& name : arm.frame_names()) {
      const Vector6d q6 = q;
      worst_fk = std::max(
          worst_fk,
          (arm.fk(q, arm.frame(name)).matrix() - puma.fk(q6, puma.frame(name)).matrix()).cwiseAbs().maxCoeff());
      worst_jacobian =
          std::max(worst_jacobian,
                   (arm.jacobian(q, arm.frame(name)) - puma.jacobian(q6, puma.frame(name))).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(worst_fk, 1e-9);
  EXPECT_LT(worst_jacobian, 1e-9);
  std::printf("PUMA, 500 joint sets x 11 frames: worst |FK difference| %.2e, worst |Jacobian difference| %.2e\n",
              worst_fk, worst_jacobian);
}

TEST(ArmModelPuma, DynamicsEqualPumaModel) {
  PumaModel puma(kPumaUrdf);
  ArmModel arm(kPumaUrdf);
  const Vector6d rotor = (Vector6d() << 0.78, 2.32, 0.58, 0.19, 0.17, 0.19).finished();
  std::mt19937_64 rng(52);
  double worst_tau = 0.0, worst_mass = 0.0, worst_qdd = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      puma.set_rotor_inertia(rotor);
      arm.set_rotor_inertia(rotor);
    }
    for (int n = 0; n < 300; ++n) {
      const Vector6d q = test::random_q(arm, rng), qd = test::random_vector(6, 2.0, rng),
                     qdd = test::random_vector(6, 5.0, rng), tau = test::random_vector(6, 50.0, rng);
      const Eigen::Vector3d g = n % 2 ? standard_gravity() : Eigen::Vector3d(1.0, -2.0, -9.0);
      worst_tau = std::max(worst_tau, (arm.rnea(q, qd, qdd, g) - puma.rnea(q, qd, qdd, g)).cwiseAbs().maxCoeff());
      worst_tau = std::max(worst_tau, (arm.gravity_torques(q, g) - puma.gravity_torques(q, g)).cwiseAbs().maxCoeff());
      worst_tau = std::max(worst_tau, (arm.coriolis(q, qd) - puma.coriolis(q, qd)).cwiseAbs().maxCoeff());
      worst_mass = std::max(worst_mass, (arm.mass_matrix(q) - puma.mass_matrix(q)).cwiseAbs().maxCoeff());
      // qdd reaches 1e5 rad/s^2 where a wrist's inertia is 1e-4 kg m^2: compared relative to its size.
      const Vector6d qdd_puma = puma.forward_dynamics(q, qd, tau, g);
      worst_qdd = std::max(worst_qdd, (arm.forward_dynamics(q, qd, tau, g) - qdd_puma).cwiseAbs().maxCoeff() /
                                          std::max(1.0, qdd_puma.cwiseAbs().maxCoeff()));
    }
  }
  EXPECT_LT(worst_tau, 1e-9);
  EXPECT_LT(worst_mass, 1e-9);
  EXPECT_LT(worst_qdd, 1e-9);
  std::printf("PUMA, 600 states: worst |torque difference| %.2e N m, |mass matrix| %.2e kg m^2, relative qdd %.2e\n",
              worst_tau, worst_mass, worst_qdd);
}

TEST(ArmModelUr5e, ForwardKinematicsEqualsThePublishedDhTable) {
  const ArmModel arm(kUr5eUrdf);
  ASSERT_EQ(arm.dof(), 6);
  EXPECT_EQ(arm.ik_method(), ArmIkMethod::kUrClosedForm);
  const double d[6] = {0.1625, 0, 0, 0.1333, 0.0997, 0.0996};
  const double a[6] = {0, -0.425, -0.3922, 0, 0, 0};
  const double alpha[6] = {kPi / 2, 0, 0, kPi / 2, -kPi / 2, 0};
  const FrameId flange = arm.frame("flange"), dev = arm.frame("dev"), knob = arm.frame("knob"),
                marker = arm.frame("marker_2");
  std::mt19937_64 rng(53);
  double worst = 0.0;
  for (int n = 0; n < 1000; ++n) {
    const JointVector q = test::random_q(arm, rng);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 6; ++i) T = T * test::standard_dh(q[i], d[i], a[i], alpha[i]);
    const std::pair<FrameId, Eigen::Isometry3d> cases[] = {{flange, T},
                                                           {dev, T * test::translation(0, 0, 0.05)},
                                                           {knob, T * test::translation(0, 0, 0.09)},
                                                           {marker, T * test::translation(-0.08, -0.08, 0.05)}};
    for (const auto& [f, expected] : cases)
      worst = std::max(worst, (arm.fk(q, f).matrix() - expected.matrix()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
  std::printf("UR5e, 1000 joint sets: worst |FK - published DH| %.2e\n", worst);
  EXPECT_NEAR(arm.limits().upper[0], 2 * kPi, 1e-12);
  EXPECT_NEAR(arm.limits().velocity[3], kPi, 1e-12);
  EXPECT_EQ(arm.limits().effort[2], 150.0);
  EXPECT_EQ(arm.limits().effort[5], 28.0);
  EXPECT_NEAR(arm.body(2).mass, 8.058, 1e-12);
  EXPECT_NEAR(arm.body(6).mass, 0.365 + 0.4 + 1.08 + 0.0763, 1e-12);  // wrist 3 + sensor, plate, knob
}

TEST(ArmModelFr3, ForwardKinematicsEqualsThePublishedCraigDhTable) {
  const ArmModel arm(kFr3Urdf);
  ASSERT_EQ(arm.dof(), 7);
  EXPECT_EQ(arm.ik_method(), ArmIkMethod::kNumerical);
  const double a[7] = {0, 0, 0, 0.0825, -0.0825, 0, 0.088};
  const double d[7] = {0.333, 0, 0.316, 0, 0.384, 0, 0};
  const double alpha[7] = {0, -kPi / 2, kPi / 2, kPi / 2, -kPi / 2, kPi / 2, kPi / 2};
  std::mt19937_64 rng(54);
  double worst = 0.0;
  for (int n = 0; n < 1000; ++n) {
    const JointVector q = test::random_q(arm, rng);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 7; ++i) T = T * test::modified_dh(q[i], d[i], a[i], alpha[i]);
    T = T * test::translation(0, 0, 0.107);
    worst = std::max(worst, (arm.fk(q).matrix() - T.matrix()).cwiseAbs().maxCoeff());
    worst = std::max(
        worst,
        (arm.fk(q, arm.frame("knob")).matrix() - (T * test::translation(0, 0, 0.09)).matrix()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(arm.limits().lower[3], -3.0421, 1e-12);
  EXPECT_NEAR(arm.limits().upper[5], 4.5169, 1e-12);
  EXPECT_EQ(arm.limits().effort[4], 12.0);
}

// The equations of motion hold together: rnea = M qdd + C qd + g, forward dynamics inverts rnea,
// M is symmetric positive definite, and gravity torques are the gradient of the potential energy
// (bodies' centres of mass from fk, by central differences) for any gravity vector.
TEST(ArmModelDynamics, EquationsOfMotionAreConsistentForEveryArm) {
  for (const std::string& path : {kPumaUrdf, kUr5eUrdf, kFr3Urdf}) {
    ArmModel arm(path);
    const int n = arm.dof();
    arm.set_rotor_inertia(JointVector::Constant(n, 0.1));
    std::mt19937_64 rng(55);
    const Eigen::Vector3d g(0.5, -1.0, -9.7);
    for (int k = 0; k < 50; ++k) {
      const JointVector q = test::random_q(arm, rng), qd = test::random_vector(n, 2.0, rng),
                        qdd = test::random_vector(n, 5.0, rng);
      const JointMatrix M = arm.mass_matrix(q);
      EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-12) << path;
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0) << path;
      const JointVector tau = arm.rnea(q, qd, qdd, g);
      const JointVector split = M * qdd + arm.coriolis(q, qd) + arm.gravity_torques(q, g);
      EXPECT_LT((tau - split).cwiseAbs().maxCoeff(), 1e-9) << path;
      EXPECT_LT((arm.forward_dynamics(q, qd, tau, g) - qdd).cwiseAbs().maxCoeff(), 1e-8) << path;
      // V(q) = -sum m g . c; tau_g = dV/dq.
      auto potential = [&](const JointVector& qq) {
        double V = 0.0;
        for (int b = 1; b <= n; ++b) V -= arm.body(b).mass * g.dot(arm.fk(qq, arm.body_frame(b)) * arm.body(b).com);
        return V;
      };
      const JointVector tau_g = arm.gravity_torques(q, g);
      for (int j = 0; j < n; ++j) {
        JointVector qp = q, qm = q;
        qp[j] += 1e-6;
        qm[j] -= 1e-6;
        EXPECT_NEAR(tau_g[j], (potential(qp) - potential(qm)) / 2e-6, 1e-6) << path << " joint " << j;
      }
    }
  }
}

class ArmModelErrors : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("arm_model_" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
  }
  // The message of the runtime_error that loading throws, or "" when it loads.
  static std::string error_of(const std::string& path, const std::string& tip = "flange",
                              const std::string& base = "base_link") {
    try {
      ArmModel model(path, tip, base);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(ArmModelErrors, NameTheFileAndWhatIsWrong) {
  const std::string missing_tip = error_of(kUr5eUrdf, "tool99");
  EXPECT_NE(missing_tip.find(kUr5eUrdf), std::string::npos) << missing_tip;
  EXPECT_NE(missing_tip.find("no link 'tool99'"), std::string::npos) << missing_tip;
  const std::string wrong_base = error_of(kUr5eUrdf, "flange", "shoulder_base");
  EXPECT_NE(wrong_base.find("no link 'shoulder_base'"), std::string::npos) << wrong_base;
  const std::string upside_down = error_of(kUr5eUrdf, "upper_arm_link", "flange");
  EXPECT_NE(upside_down.find("is not below link 'flange'"), std::string::npos) << upside_down;
  EXPECT_NE(upside_down.find(kUr5eUrdf), std::string::npos) << upside_down;
  const std::string no_joint = error_of(kUr5eUrdf, "knob", "flange");
  EXPECT_NE(no_joint.find("no moving joint"), std::string::npos) << no_joint;

  const std::string garbage = write("garbage.urdf", "<robot name='x'><link name='a'>");
  EXPECT_NE(error_of(garbage).find(garbage + ": not a valid URDF"), std::string::npos) << error_of(garbage);
  const std::string absent = (dir / "absent.urdf").string();
  EXPECT_NE(error_of(absent).find(absent + ": cannot open the file"), std::string::npos) << error_of(absent);

  const std::string links = "<link name='base_link'/><link name='a'/><link name='b'/><link name='flange'/>";
  const std::string to_a =
      "<joint name='j1' type='revolute'><parent link='base_link'/><child link='a'/>"
      "<axis xyz='0 0 1'/><limit lower='-1' upper='1' velocity='1' effort='1'/></joint>";
  const std::string to_flange = "<joint name='jf' type='fixed'><parent link='a'/><child link='flange'/></joint>";
  const std::string continuous = write("continuous.urdf", "<robot name='c'>" + links + to_a + to_flange +
                                                              "<joint name='j2' type='continuous'><parent link='a'/>"
                                                              "<child link='b'/><axis xyz='0 1 0'/></joint></robot>");
  // j2 hangs off the chain to the flange, and has no limits either: the branch is named first.
  EXPECT_NE(error_of(continuous).find("joint 'j2' (continuous) at link 'a' is off the chain"), std::string::npos)
      << error_of(continuous);
  EXPECT_NE(error_of(continuous, "b").find("joint 'j2' (continuous) has no <limit>"), std::string::npos)
      << error_of(continuous, "b");
  const std::string three = "<link name='base_link'/><link name='a'/><link name='flange'/>";
  const std::string floating = write("floating.urdf", "<robot name='f'>" + three + to_a +
                                                          "<joint name='j2' type='floating'><parent link='a'/>"
                                                          "<child link='flange'/></joint></robot>");
  EXPECT_NE(error_of(floating).find("joint 'j2' is floating"), std::string::npos) << error_of(floating);
  EXPECT_NE(error_of(floating).find(floating), std::string::npos);
}

TEST(ArmModelAllocation, HotCallsAllocateNothingAfterConstruction) {
  for (const std::string& path : {kPumaUrdf, kUr5eUrdf, kFr3Urdf}) {
    const ArmModel arm(path);
    const int n = arm.dof();
    std::mt19937_64 rng(56);
    const JointVector q = test::random_q(arm, rng, 0.3), qd = test::random_vector(n, 1.0, rng);
    const Eigen::Isometry3d pose = arm.fk(q);
    const JointVector near = q + test::random_vector(n, 0.01, rng);
    const Eigen::VectorXd q_heap = q;  // a caller's VectorXd binds without a copy as well
    double sink = 0.0;
    g_mallocs = 0;
    g_counting = true;
    sink += arm.fk(q_heap, arm.frame("knob")).translation().x();
    sink += arm.jacobian(q).sum();
    sink += arm.dls_step(q, pose, 0.01).sum();
    const ArmIkResult nearest = arm.ik_nearest(pose, near);
    const ArmIkSolutions all = arm.ik(pose, near);
    sink += arm.rnea(q, qd, qd).sum() + arm.mass_matrix(q).sum() + arm.gravity_torques(q).sum();
    sink += arm.coriolis(q, qd).sum() + arm.forward_dynamics(q, qd, qd).sum();
    g_counting = false;
    EXPECT_EQ(g_mallocs.load(), 0) << path;
    EXPECT_TRUE(nearest.ok()) << path;
    EXPECT_GT(all.count, 0) << path;
    EXPECT_TRUE(std::isfinite(sink));
  }
}

}  // namespace
}  // namespace wysiwyf::robot
