// The camera's pose in the robot's base frame from a board on the PUMA's plate: the pose set the
// tool generates (reached by the arm's IK, the board in view), corners projected through the true
// camera with detection noise, the fit against the truth (the shipped camera pose perturbed by a
// seeded error, the board's mount off its nominal place); too few poses, poses without rotation
// and a camera that moved mid-way refused with the reason.
#include <gtest/gtest.h>

#include <cstdio>

#include "calibration/robot_world_fit.hpp"
#include "calibration/robot_world_poses.hpp"
#include "calibration_truth.hpp"

namespace wysiwyf::test {

namespace cal = vision::calibration;

namespace {

Eigen::Isometry3d small_motion(std::mt19937& rng, double metres, double degrees) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d d = Eigen::Isometry3d::Identity();
  d.linear() =
      Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  d.translation() = metres * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  return d;
}

class RobotWorld : public ::testing::Test {
 protected:
  RobotWorld()
      : arm(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "dev"),
        flange(arm.frame("flange")),
        target(cal::CharucoSpec{}),
        shipped(cal::load_camera_file(std::string(WYSIWYF_CONFIG_DIR) + "/calibration/sim_camera.yaml")) {
    home = Eigen::VectorXd(6);
    home << 0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254;  // hardware/sim.yaml's initial_q
    const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
    nominal_flange_T_board = arm.fk(q0, flange).inverse() * arm.fk(q0, arm.frame("dev")) * cal::dev_T_board(target);
  }

  // Corners the camera (base_T_eye) sees of the board (flange_T_board) at each pose, with noise.
  std::vector<cal::FlangeView> views(const std::vector<robot::JointVector>& poses, const Eigen::Isometry3d& base_T_eye,
                                     const Eigen::Isometry3d& flange_T_board, std::mt19937& rng,
                                     const cal::CameraIntrinsics& camera, double sigma = 0.2) {
    std::normal_distribution<float> noise(0.0f, static_cast<float>(sigma));
    std::vector<cal::FlangeView> out;
    for (const auto& q : poses) {
      cal::FlangeView v;
      v.label = "pose " + std::to_string(out.size() + 1);
      v.base_T_flange = arm.fk(q, flange);
      const auto p = cal::project(camera, base_T_eye.inverse() * v.base_T_flange * flange_T_board, target.corners());
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p[i].x >= 0 && p[i].y >= 0 && p[i].x < camera.size.width && p[i].y < camera.size.height) {
          v.corners.emplace_back(p[i].x + noise(rng), p[i].y + noise(rng));
          v.ids.push_back(static_cast<int>(i));
        }
      out.push_back(v);
    }
    return out;
  }

  robot::ArmModel arm;
  robot::FrameId flange;
  cal::CharucoTarget target;
  cal::CameraFile shipped;
  Eigen::VectorXd home;
  Eigen::Isometry3d nominal_flange_T_board;
};

}  // namespace

// 20 generated poses, corners with 0.2 px noise: the camera within 0.5 mm and 0.05 deg of the
// truth, every pose's error reported.
TEST_F(RobotWorld, CameraToBaseWithinHalfAMillimetreAndAHundredthOfADegree) {
  for (unsigned seed : {31u, 32u}) {
    std::mt19937 rng(seed);
    const cal::CameraIntrinsics camera = perturbed_sim_camera(seed);
    const Eigen::Isometry3d base_T_eye = *shipped.base_T_eye * small_motion(rng, 0.02, 2.0);
    const Eigen::Isometry3d flange_T_board = nominal_flange_T_board * small_motion(rng, 0.003, 1.0);
    const auto poses =
        cal::robot_world_poses(arm, home, flange, nominal_flange_T_board, *shipped.base_T_eye, camera, target, 20, rng);
    ASSERT_EQ(poses.size(), 20u);
    for (const auto& q : poses) EXPECT_TRUE(arm.limits().within(q));
    const cal::RobotWorldFit fit =
        cal::fit_robot_world(views(poses, base_T_eye, flange_T_board, rng, camera), target, camera);
    ASSERT_TRUE(fit.accepted) << cal::describe(fit, {});
    const Eigen::Isometry3d d = base_T_eye.inverse() * fit.base_T_eye;
    const double mm = 1e3 * (fit.base_T_eye.translation() - base_T_eye.translation()).norm();
    const double deg = Eigen::AngleAxisd(d.linear()).angle() * 180 / M_PI;
    EXPECT_LE(mm, 0.5) << cal::describe(fit, {});
    EXPECT_LE(deg, 0.05) << cal::describe(fit, {});
    EXPECT_LE(1e3 * (fit.flange_T_board.translation() - flange_T_board.translation()).norm(), 0.5);
    for (const auto& p : fit.poses) EXPECT_GT(p.rms, 0) << p.label;
    EXPECT_LT(fit.rms, 0.35);  // 0.2 px per axis: 0.28 px per corner
    std::printf("seed %u: camera error %.3f mm %.4f deg, rms %.3f px, rotation spread %.1f deg\n", seed, mm, deg,
                fit.rms, fit.rotation_spread);
  }
}

TEST_F(RobotWorld, TooFewPosesAndNoRotationAreRefused) {
  std::mt19937 rng(33);
  const cal::CameraIntrinsics camera = perturbed_sim_camera(33);
  const auto poses =
      cal::robot_world_poses(arm, home, flange, nominal_flange_T_board, *shipped.base_T_eye, camera, target, 5, rng);
  cal::RobotWorldFit fit =
      cal::fit_robot_world(views(poses, *shipped.base_T_eye, nominal_flange_T_board, rng, camera), target, camera);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("5 usable poses of 5; expected at least 8"), std::string::npos) << fit.refusal;

  // The board carried without turning: translations alone cannot tell the camera from the mount.
  std::vector<robot::JointVector> shifted;
  const Eigen::Isometry3d start = arm.fk(poses.front(), flange);
  for (int i = 0; i < 10; ++i) {
    Eigen::Isometry3d t = start;
    t.translation() += Eigen::Vector3d(0.02 * (i % 3), 0.02 * (i / 3 % 3), 0.01 * (i % 2));
    const auto ik = arm.ik_nearest(t, poses.front(), flange);
    ASSERT_TRUE(ik.ok());
    shifted.push_back(ik.q);
  }
  fit = cal::fit_robot_world(views(shifted, *shipped.base_T_eye, nominal_flange_T_board, rng, camera), target, camera);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("about its least-turned axis"), std::string::npos) << fit.refusal;
}

// The camera knocked 3 mm and 0.3 deg after the tenth of twenty poses: refused, naming where.
TEST_F(RobotWorld, ACameraMovedMidWayIsRefusedNamingWhere) {
  std::mt19937 rng(34);
  const cal::CameraIntrinsics camera = perturbed_sim_camera(34);
  const Eigen::Isometry3d base_T_eye = *shipped.base_T_eye;
  const auto poses =
      cal::robot_world_poses(arm, home, flange, nominal_flange_T_board, base_T_eye, camera, target, 20, rng);
  ASSERT_EQ(poses.size(), 20u);
  auto seen = views({poses.begin(), poses.begin() + 10}, base_T_eye, nominal_flange_T_board, rng, camera);
  const auto after = views({poses.begin() + 10, poses.end()}, base_T_eye * small_motion(rng, 0.003, 0.3),
                           nominal_flange_T_board, rng, camera);
  for (std::size_t i = 0; i < after.size(); ++i) {
    seen.push_back(after[i]);
    seen.back().label = "pose " + std::to_string(11 + i);
  }
  const cal::RobotWorldFit fit = cal::fit_robot_world(seen, target, camera);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("moved between pose 10 and pose 11"), std::string::npos) << cal::describe(fit, {});
  std::printf("%s\n", fit.refusal.c_str());
}

TEST_F(RobotWorld, HostileViewsAreLeftOutNamed) {
  std::mt19937 rng(35);
  const cal::CameraIntrinsics camera = perturbed_sim_camera(35);
  const auto poses =
      cal::robot_world_poses(arm, home, flange, nominal_flange_T_board, *shipped.base_T_eye, camera, target, 10, rng);
  auto seen = views(poses, *shipped.base_T_eye, nominal_flange_T_board, rng, camera);
  seen[2].ids[0] = 9999;
  seen[3].base_T_flange.translation().x() = NAN;
  seen[4].corners.resize(3), seen[4].ids.resize(3);
  const cal::RobotWorldFit fit = cal::fit_robot_world(seen, target, camera);
  EXPECT_EQ(fit.poses[2].note, "corner ids that are not the board's");
  EXPECT_EQ(fit.poses[3].note, "a non-finite flange pose");
  EXPECT_EQ(fit.poses[4].note, "too few corners: 3");
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("7 usable poses of 10"), std::string::npos) << fit.refusal;
}

}  // namespace wysiwyf::test
