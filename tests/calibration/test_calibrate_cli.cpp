// `wysiwyf calibrate` as a lab runs it, on recorded data made from simulated truth: the wrist's
// poses, filled-in readings and the rewritten scene; a folder of board images to a camera file;
// the robot-world poses, an image at each and the camera's pose in that file (camera_fixed's); a
// stereo pair's two folders to its two rectified files.
// Refusals exit 1 with the reason, usage mistakes 2.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>

#include <opencv2/imgcodecs.hpp>

#include "calibration/board_view_sim.hpp"
#include "calibration/flange_views_file.hpp"
#include "calibration/robot_world_poses.hpp"
#include "calibrate_cli.hpp"
#include "calibration_truth.hpp"
#include "camera_component.hpp"
#include "scene/scene.hpp"
#include "wrist_calibration/wrist_poses.hpp"
#include "wrist_calibration/wrist_readings_file.hpp"

namespace wysiwyf::test {

namespace cal = vision::calibration;
namespace fs = std::filesystem;

namespace {

const std::string kConfig = WYSIWYF_CONFIG_DIR;

}  // namespace

TEST(CalibrateCli, WristPosesReadingsAndTheScene) {
  const fs::path dir = scratch("cli_wrist");
  const CliRun poses = calibrate("wrist-poses --home 0,-0.6,0.3,0,0.5,0 --out " + (dir / "readings.yaml").string());
  ASSERT_EQ(poses.status, 0) << poses.output;
  // The lab's readings: bias, the tool (1.25 kg, 2 cm out), noise.
  const robot::ArmModel arm(kConfig + "/robots/puma560.urdf", "ft_sensor");
  auto samples = robot::load_wrist_readings((dir / "readings.yaml").string(), 6);
  ASSERT_EQ(samples.size(), 12u);
  std::mt19937 rng(41);
  std::normal_distribution<double> noise(0, 0.03);
  for (auto& s : samples) {
    const Eigen::Vector3d w = 1.25 * robot::gravity_in_frame(arm, s.joints, arm.frame("ft_sensor"));
    s.wrench.head<3>() = Eigen::Vector3d(0.8, -1.1, 2.5) + w + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    s.wrench.tail<3>() = Eigen::Vector3d(0.02, 0.01, -0.03) + Eigen::Vector3d(0, 0, 0.02).cross(w);
  }
  std::ofstream(dir / "readings.yaml") << robot::wrist_readings_yaml(samples);
  const CliRun fit = calibrate("wrist --readings " + (dir / "readings.yaml").string() + " --scene " + kConfig +
                               "/scenes/display_demo.yaml --out " + (dir / "scene.yaml").string());
  ASSERT_EQ(fit.status, 0) << fit.output;
  EXPECT_NE(fit.output.find("pose 12"), std::string::npos) << fit.output;
  const auto scene = haptics::load_scene((dir / "scene.yaml").string());
  EXPECT_NEAR(scene.device.tool_mass, 1.25, 0.02 * 1.25);
  EXPECT_NEAR(scene.device.tool_com.z(), 0.02, 0.001);

  samples.resize(4);
  std::ofstream(dir / "few.yaml") << robot::wrist_readings_yaml(samples);
  const CliRun few = calibrate("wrist --readings " + (dir / "few.yaml").string());
  EXPECT_EQ(few.status, 1) << few.output;
  EXPECT_NE(few.output.find("refused: 4 poses"), std::string::npos) << few.output;
  std::ofstream(dir / "bad.yaml") << "readings:\n  - {joints: [0, 0], wrench: [0, 0, 0, 0, 0, 0]}\n";
  const CliRun bad = calibrate("wrist --readings " + (dir / "bad.yaml").string());
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.yaml:2:14: readings[0] joints: expected a list of 6 numbers"), std::string::npos)
      << bad.output;
  EXPECT_EQ(calibrate("wrist").status, 2);
  EXPECT_EQ(calibrate("wrist-poses --home 0,1").status, 2);
  EXPECT_EQ(calibrate("focus").status, 2);
}

// Images of the board through a known camera, then its pose from images at the generated poses.
TEST(CalibrateCli, IntrinsicsThenCameraBaseFromImages) {
  const fs::path dir = scratch("cli_camera");
  const cal::CharucoTarget target(cal::CharucoSpec{});
  const cal::CameraIntrinsics truth = perturbed_sim_camera(42);
  const cal::BoardViewSim sim(target, truth);
  std::mt19937 rng(42);
  fs::create_directories(dir / "board");
  int i = 0;
  for (const auto& pose : cal::board_view_poses(target, truth, 32, rng)) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%02d.png", ++i);
    cv::imwrite((dir / "board" / name).string(), sim.render(pose, {}, rng));
  }
  const CliRun intrinsics =
      calibrate("intrinsics --images " + (dir / "board").string() + " --out " + (dir / "camera.yaml").string());
  ASSERT_EQ(intrinsics.status, 0) << intrinsics.output;
  EXPECT_NE(intrinsics.output.find("view_32.png"), std::string::npos);
  const cal::CameraFile camera = cal::load_camera_file((dir / "camera.yaml").string());
  EXPECT_NEAR(camera.intrinsics.camera_matrix(0, 0) / truth.camera_matrix(0, 0), 1.0, 0.003);

  // A rough pose of the camera (the shipped one) to plan the poses; the truth is 1 cm and 1 deg off.
  const CliRun planned = calibrate("camera-base-poses --camera " + kConfig + "/calibration/sim_camera.yaml" +
                                   " --home 0.344932,0.380005,-3.43618,0.346061,1.49034,3.11254 --count 16 --out " +
                                   (dir / "views.yaml").string());
  ASSERT_EQ(planned.status, 0) << planned.output;
  const robot::ArmModel arm(kConfig + "/robots/puma560.urdf", "dev");
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
  const Eigen::Isometry3d flange_T_board =
      arm.fk(q0, arm.frame("flange")).inverse() * arm.fk(q0, arm.frame("dev")) * cal::dev_T_board(target);
  Eigen::Isometry3d base_T_eye = *cal::load_camera_file(kConfig + "/calibration/sim_camera.yaml").base_T_eye *
                                 Eigen::Translation3d(0.006, -0.008, 0.004) *
                                 Eigen::AngleAxisd(0.017, Eigen::Vector3d(1, 2, 3).normalized());
  for (const auto& v : cal::load_flange_views((dir / "views.yaml").string(), 6)) {
    const Eigen::Isometry3d eye_T_board = base_T_eye.inverse() * arm.fk(v.joints, arm.frame("flange")) * flange_T_board;
    cv::imwrite(v.image, sim.render(eye_T_board, {}, rng));
  }
  const CliRun fitted = calibrate("camera-base --camera " + (dir / "camera.yaml").string() + " --views " +
                                  (dir / "views.yaml").string() + " --out " + (dir / "camera_base.yaml").string());
  ASSERT_EQ(fitted.status, 0) << fitted.output;
  const cal::CameraFile result = cal::load_camera_file((dir / "camera_base.yaml").string());
  ASSERT_TRUE(result.base_T_eye);
  const double mm = 1e3 * (result.base_T_eye->translation() - base_T_eye.translation()).norm();
  const double deg =
      Eigen::AngleAxisd(base_T_eye.linear().transpose() * result.base_T_eye->linear()).angle() * 180 / M_PI;
  std::printf("from images: camera error %.3f mm %.4f deg\n", mm, deg);
  EXPECT_LE(mm, 1.0) << fitted.output;
  EXPECT_LE(deg, 0.1) << fitted.output;
  EXPECT_EQ(result.intrinsics.camera_matrix, camera.intrinsics.camera_matrix);

  // An image of another camera (another size) among the views: said, nothing written.
  const auto views = cal::load_flange_views((dir / "views.yaml").string(), 6);
  cv::imwrite(views.front().image, cv::Mat(240, 320, CV_8UC1, cv::Scalar(128)));
  const CliRun other = calibrate("camera-base --camera " + (dir / "camera.yaml").string() + " --views " +
                                 (dir / "views.yaml").string() + " --out " + (dir / "other.yaml").string());
  EXPECT_EQ(other.status, 2) << other.output;
  EXPECT_NE(other.output.find("320x240 px; expected the calibrated camera's 640x480"), std::string::npos)
      << other.output;
  EXPECT_FALSE(fs::exists(dir / "other.yaml"));

  const CliRun missing = calibrate("camera-base --camera " + (dir / "camera.yaml").string() + " --views " +
                                   (dir / "nowhere.yaml").string() + " --out " + (dir / "x.yaml").string());
  EXPECT_EQ(missing.status, 2) << missing.output;
}

// calibrate stereo from two folders of images of the same board positions (names pair them), each
// camera's file from `calibrate intrinsics` (here the truth): both files written with their
// rectification, the right one's projection holding the baseline, and read back as the camera
// component reads them; a folder whose right camera was knocked half-way is refused, exit 1.
TEST(CalibrateCli, StereoFromTwoFoldersWritesBothRectifiedFiles) {
  const fs::path dir = scratch("cli_stereo");
  const cal::CharucoTarget target(cal::CharucoSpec{});
  const cal::CameraIntrinsics left = perturbed_sim_camera(51), right = perturbed_sim_camera(151);
  cal::save_camera_file((dir / "left_in.yaml").string(), {left, std::nullopt, std::nullopt, std::nullopt}, "truth");
  cal::save_camera_file((dir / "right_in.yaml").string(), {right, std::nullopt, std::nullopt, std::nullopt}, "truth");
  Eigen::Isometry3d right_T_left(Eigen::AngleAxisd(0.006, Eigen::Vector3d::UnitY()));
  right_T_left.translation() = Eigen::Vector3d(-0.06, 0.0003, 0.0005);
  const cal::BoardViewSim sim_left(target, left), sim_right(target, right);
  const auto render = [&](const std::string& folder, double knock_after_half) {
    std::mt19937 rng(51);
    fs::create_directories(dir / folder / "left");
    fs::create_directories(dir / folder / "right");
    int i = 0;
    for (const auto& left_T_board : cal::board_view_poses(target, left, 20, rng)) {
      char name[32];
      std::snprintf(name, sizeof name, "pair_%02d.png", ++i);
      const Eigen::Isometry3d knock(Eigen::AngleAxisd(i > 10 ? knock_after_half : 0.0, Eigen::Vector3d::UnitX()));
      cv::imwrite((dir / folder / "left" / name).string(), sim_left.render(left_T_board, {}, rng));
      cv::imwrite((dir / folder / "right" / name).string(),
                  sim_right.render(knock * right_T_left * left_T_board, {}, rng));
    }
  };
  const auto stereo = [&](const std::string& folder) {
    return calibrate("stereo --left " + (dir / "left_in.yaml").string() + " --right " +
                     (dir / "right_in.yaml").string() + " --left-images " + (dir / folder / "left").string() +
                     " --right-images " + (dir / folder / "right").string() + " --out-left " +
                     (dir / folder / "left.yaml").string() + " --out-right " + (dir / folder / "right.yaml").string());
  };
  render("good", 0);
  const CliRun good = stereo("good");
  ASSERT_EQ(good.status, 0) << good.output;
  EXPECT_NE(good.output.find("pair_20.png: epipolar"), std::string::npos) << good.output;
  const cal::CameraFile l = cal::load_camera_file((dir / "good" / "left.yaml").string());
  const cal::CameraFile r = cal::load_camera_file((dir / "good" / "right.yaml").string());
  ASSERT_TRUE(l.rectification && l.projection && r.rectification && r.projection);
  EXPECT_NEAR(-(*r.projection)(0, 3) / (*r.projection)(0, 0), 0.06, 0.0005) << "the baseline";
  EXPECT_NEAR(r.intrinsics.camera_matrix(0, 0), right.camera_matrix(0, 0), 1e-9) << "the intrinsics kept";
  // The camera component (hardware/real.yaml's stereo cameras) publishes the right one's R and P.
  msg::CameraInfo ci;
  ASSERT_TRUE(camera_info_of(dir / "good" / "right.yaml", dir, ci));
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(ci.p()[static_cast<std::size_t>(i)], (*r.projection)(i / 4, i % 4), 1e-9);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(ci.r()[static_cast<std::size_t>(i)], (*r.rectification)(i / 3, i % 3), 1e-9);

  render("knocked", 0.3 * M_PI / 180);
  const CliRun knocked = stereo("knocked");
  EXPECT_EQ(knocked.status, 1) << knocked.output;
  EXPECT_NE(knocked.output.find("refused: epipolar error"), std::string::npos) << knocked.output;
  EXPECT_FALSE(fs::exists(dir / "knocked" / "right.yaml"));
}

}  // namespace wysiwyf::test
