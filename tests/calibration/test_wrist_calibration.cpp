// The wrist sensor's calibration from simulated static poses of the PUMA 560: a seeded bias, tool
// and sensor noise, the readings made as arm_sim makes them (the tool's weight in the sensor
// frame from the arm's kinematics); the fit against that truth, and bad pose sets refused.
#include <gtest/gtest.h>

#include <random>

#include "wrist_calibration/tool_load_fit.hpp"
#include "wrist_calibration/wrist_poses.hpp"
#include "wrist_calibration/wrist_readings_file.hpp"

namespace wr = wysiwyf::robot;

namespace {

struct Truth {
  Eigen::Vector3d force_bias{1.7, -2.3, 4.1};
  Eigen::Vector3d torque_bias{0.12, -0.05, 0.031};
  double mass = 1.1563;
  Eigen::Vector3d com{0.002, -0.001, 0.01665};
};

class WristCalibration : public ::testing::Test {
 protected:
  WristCalibration()
      : arm(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "dev"), sensor(arm.frame("ft_sensor")) {
    home = Eigen::VectorXd::Zero(arm.dof());
    home << 0.0, -0.6, 0.3, 0.0, 0.5, 0.0;
  }

  // What the sensor reads at q: bias + the tool's weight and moment + Gaussian noise.
  wr::WristSample reading(const Eigen::VectorXd& q, const Truth& t, std::mt19937& rng, double force_sigma,
                          double torque_sigma, const std::string& label) {
    std::normal_distribution<double> normal;
    const Eigen::Vector3d g = wr::gravity_in_frame(arm, q, sensor);
    wr::WristSample s;
    s.label = label;
    s.joints = q;
    s.wrench.head<3>() = t.force_bias + t.mass * g;
    s.wrench.tail<3>() = t.torque_bias + t.com.cross(t.mass * g);
    for (int i = 0; i < 3; ++i) s.wrench[i] += force_sigma * normal(rng);
    for (int i = 3; i < 6; ++i) s.wrench[i] += torque_sigma * normal(rng);
    return s;
  }

  std::vector<wr::WristSample> readings(const std::vector<wr::JointVector>& poses, const Truth& t, unsigned seed,
                                        double force_sigma = 0.05, double torque_sigma = 0.002) {
    std::mt19937 rng(seed);
    std::vector<wr::WristSample> out;
    for (std::size_t i = 0; i < poses.size(); ++i)
      out.push_back(reading(poses[i], t, rng, force_sigma, torque_sigma, "pose " + std::to_string(i + 1)));
    return out;
  }

  wr::ArmModel arm;
  wr::FrameId sensor;
  Eigen::VectorXd home;
};

}  // namespace

// Twelve generated poses, readings with arm_sim's noise (0.05 N, 0.002 N m per axis): bias within
// 0.05 N, mass within 2 %, the centre of mass within a millimetre; every pose's residual reported.
TEST_F(WristCalibration, RecoversBiasMassAndCentreOfMassFromTwelvePoses) {
  for (unsigned seed : {1u, 2u, 3u}) {
    Truth t;
    std::mt19937 rng(100 + seed);
    std::uniform_real_distribution<double> u(-1, 1);
    t.force_bias += Eigen::Vector3d(u(rng), u(rng), u(rng));
    t.mass *= 1.0 + 0.2 * u(rng);
    const auto poses = wr::wrist_calibration_poses(arm, home, sensor, 12);
    ASSERT_EQ(poses.size(), 12u);
    const wr::ToolLoadFit fit = wr::fit_tool_load(wr::wrist_readings(arm, sensor, readings(poses, t, seed)));
    ASSERT_TRUE(fit.accepted) << wr::describe(fit, {});
    EXPECT_LE((fit.force_bias - t.force_bias).norm(), 0.05) << wr::describe(fit, {});
    EXPECT_LE((fit.torque_bias - t.torque_bias).norm(), 0.005) << wr::describe(fit, {});
    EXPECT_LE(std::abs(fit.tool_mass - t.mass) / t.mass, 0.02) << wr::describe(fit, {});
    EXPECT_LE((fit.tool_com - t.com).norm(), 0.001) << wr::describe(fit, {});
    ASSERT_EQ(fit.residuals.size(), 12u);
    for (const auto& r : fit.residuals) EXPECT_LT(r.force, 0.3) << r.label;
    EXPECT_LT(fit.condition, 3.0);
    std::printf("seed %u: bias error %.4f N, mass error %.3f %%, com error %.3f mm, condition %.2f\n", seed,
                (fit.force_bias - t.force_bias).norm(), 100 * std::abs(fit.tool_mass - t.mass) / t.mass,
                1e3 * (fit.tool_com - t.com).norm(), fit.condition);
  }
}

// The generated poses stay within the joint limits and point gravity every way in the sensor.
TEST_F(WristCalibration, GeneratedPosesAreReachableAndSpreadGravity) {
  const auto poses = wr::wrist_calibration_poses(arm, home, sensor, 8);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& q : poses) {
    EXPECT_TRUE(arm.limits().within(q));
    sum += wr::gravity_in_frame(arm, q, sensor).normalized();
  }
  EXPECT_LT(sum.norm() / poses.size(), 0.35);  // all one way would be 1
  EXPECT_THROW(wr::wrist_calibration_poses(arm, Eigen::VectorXd::Zero(3), sensor, 8), std::invalid_argument);
}

// Too few poses, and poses that turn the last joint only, are refused with the reason; so is a pose taken while something pushed.
TEST_F(WristCalibration, RefusesTooFewPosesPoorDirectionsAndAPushedPose) {
  Truth t;
  const auto poses = wr::wrist_calibration_poses(arm, home, sensor, 12);
  const std::vector<wr::JointVector> four(poses.begin(), poses.begin() + 4);
  wr::ToolLoadFit fit = wr::fit_tool_load(wr::wrist_readings(arm, sensor, readings(four, t, 7)));
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("4 poses; expected at least 6"), std::string::npos) << fit.refusal;

  // Turning the last joint alone: gravity sweeps a cone about the sensor's z axis, its z part never
  // changes, and the z bias cannot be told from the mass.
  std::vector<wr::JointVector> about_gravity;
  Eigen::VectorXd q = home;
  for (int k = 0; k < 8; ++k) {
    q[5] = -2.5 + 0.7 * k;
    about_gravity.push_back(q);
  }
  fit = wr::fit_tool_load(wr::wrist_readings(arm, sensor, readings(about_gravity, t, 8)));
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("condition number"), std::string::npos) << fit.refusal;

  auto pushed = readings(poses, t, 9);
  pushed[5].wrench[1] += 3.0;  // a hand on the plate at pose 6
  fit = wr::fit_tool_load(wr::wrist_readings(arm, sensor, pushed));
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("pose 6: force residual"), std::string::npos) << fit.refusal;
  EXPECT_NE(wr::describe(fit, {}).find("over the limit"), std::string::npos);
}

// A template never filled in (every reading zero), non-finite readings and a zero gravity come
// back refused, never thrown.
TEST_F(WristCalibration, NonFiniteReadingsAreRefused) {
  std::vector<wr::WristReading> r(8);
  for (std::size_t i = 0; i < r.size(); ++i) {
    r[i].label = "pose " + std::to_string(i + 1);
    r[i].gravity_sensor = Eigen::Vector3d(0, 0, -9.81);
  }
  wr::ToolLoadFit zero = wr::fit_tool_load(r);
  EXPECT_NE(zero.refusal.find("every reading is exactly zero"), std::string::npos) << zero.refusal;
  for (auto& x : r) x.force.z() = -11.3;
  r[2].force.x() = NAN;
  wr::ToolLoadFit fit = wr::fit_tool_load(r);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("pose 3: a non-finite"), std::string::npos) << fit.refusal;
  r[2].force.x() = 0;
  r[4].gravity_sensor.setZero();
  fit = wr::fit_tool_load(r);
  EXPECT_NE(fit.refusal.find("pose 5: zero gravity"), std::string::npos) << fit.refusal;
}
