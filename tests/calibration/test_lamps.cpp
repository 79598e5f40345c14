// The plate's lamp positions on the flange (tracking mode's markers) from a fixed camera watching
// the lamps while the PUMA moves through the robot-world poses: the truth is the URDF's marker_*
// links moved by up to 2 mm (seeded), the lamps' centroids carry 0.2 px of noise: every lamp
// within 0.3 mm from 40 poses. A lamp misread in one pose, and too few views, are refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "calibration/lamp_fit.hpp"
#include "calibration/robot_world_poses.hpp"
#include "calibration_truth.hpp"

namespace wysiwyf::test {

namespace cal = vision::calibration;

namespace {

struct LampRig {
  robot::ArmModel arm{std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "dev"};
  robot::FrameId flange = arm.frame("flange");
  cal::CameraFile camera = cal::load_camera_file(std::string(WYSIWYF_CONFIG_DIR) + "/calibration/sim_camera.yaml");
  std::vector<Eigen::Vector3d> nominal, truth;

  explicit LampRig(unsigned seed) {
    const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.002, 0.002);
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d p =
          (arm.fk(q0, flange).inverse() * arm.fk(q0, arm.frame("marker_" + std::to_string(i)))).translation();
      nominal.push_back(p);
      truth.push_back(p + Eigen::Vector3d(u(rng), u(rng), u(rng)));
    }
  }

  std::vector<cal::LampView> views(int count, unsigned seed, double sigma = 0.2) {
    Eigen::VectorXd home(6);
    home << 0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254;  // hardware/sim.yaml's initial_q
    const cal::CharucoTarget target(cal::CharucoSpec{});
    const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
    const Eigen::Isometry3d flange_T_board =
        arm.fk(q0, flange).inverse() * arm.fk(q0, arm.frame("dev")) * cal::dev_T_board(target);
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, sigma);
    std::vector<cal::LampView> out;
    for (const auto& q : cal::robot_world_poses(arm, home, flange, flange_T_board, *camera.base_T_eye,
                                                camera.intrinsics, target, count, rng)) {
      cal::LampView v;
      v.label = "pose " + std::to_string(out.size() + 1);
      v.base_T_flange = arm.fk(q, flange);
      const Eigen::Isometry3d eye_T_flange = camera.base_T_eye->inverse() * v.base_T_flange;
      for (const auto& p : truth) {
        const auto px = cal::project(
            camera.intrinsics, eye_T_flange,
            {cv::Point3f(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()))});
        v.lamp.emplace_back(cv::Point2d(px[0].x + noise(rng), px[0].y + noise(rng)));
      }
      out.push_back(v);
    }
    return out;
  }
};

}  // namespace

// 40 poses: every lamp within 0.3 mm, and the camera's pose found with them (about 0.4 mm: four
// lamps pin a camera less than a board's corners do; `calibrate camera-base` is for the camera).
TEST(Lamps, EveryLampOnTheFlangeWithinAThirdOfAMillimetreFromFortyPoses) {
  for (unsigned seed : {31u, 32u}) {
    LampRig rig(seed);
    const cal::LampFit fit = cal::fit_lamps(rig.views(40, seed), rig.camera.intrinsics, rig.nominal);
    ASSERT_TRUE(fit.accepted) << fit.refusal;
    double worst = 0;
    for (std::size_t i = 0; i < rig.truth.size(); ++i)
      worst = std::max(worst, (fit.flange_p_lamp[i] - rig.truth[i]).norm());
    const double camera_error = (fit.base_T_eye.translation() - rig.camera.base_T_eye->translation()).norm();
    std::printf("seed %u: worst lamp %.3f mm (the nominal one was %.3f mm off), camera %.3f mm, RMS %.3f px\n", seed,
                worst * 1e3, (rig.nominal[0] - rig.truth[0]).norm() * 1e3, camera_error * 1e3, fit.rms);
    EXPECT_LE(worst, 0.0003);
    EXPECT_LE(camera_error, 0.001);
  }
}

TEST(Lamps, AMisreadLampAndTooFewViewsAreRefused) {
  LampRig rig(33);
  std::vector<cal::LampView> views = rig.views(20, 33);
  views[7].lamp[2]->x += 6;  // another bright spot taken for lamp 2
  const cal::LampFit fit = cal::fit_lamps(views, rig.camera.intrinsics, rig.nominal);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("pose 8:"), std::string::npos) << fit.refusal;
  views.resize(6);
  EXPECT_NE(cal::fit_lamps(views, rig.camera.intrinsics, rig.nominal).refusal.find("6 views; expected at least 10"),
            std::string::npos);
}

}  // namespace wysiwyf::test
