// The calibration file the steps write is the one the pipelines read: written by
// save_camera_file, read back by load_camera_file, by the camera component (camera_info) and by
// camera_fixed (eye_T_base); the shipped files load; hostile files are refused naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "calibration/camera_file.hpp"
#include "calibration_truth.hpp"
#include "camera_component.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

namespace cal = vision::calibration;

namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

cal::CameraFile calibrated() {
  cal::CameraFile f;
  f.intrinsics = perturbed_sim_camera(21);
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  base_T_eye.linear() = Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  base_T_eye.translation() = Eigen::Vector3d(1.6012, -0.3497, 0.7031);
  f.base_T_eye = base_T_eye;
  return f;
}

}  // namespace

TEST(CameraFile, ShippedFilesLoad) {
  for (const char* name : {"sim_camera.yaml", "stereo_left.yaml", "stereo_right.yaml"}) {
    const auto f = cal::load_camera_file(std::string(WYSIWYF_CONFIG_DIR) + "/calibration/" + name);
    EXPECT_EQ(f.intrinsics.size, cv::Size(640, 480)) << name;
    EXPECT_EQ(f.intrinsics.camera_matrix(0, 0), 600) << name;
  }
  EXPECT_TRUE(cal::load_camera_file(std::string(WYSIWYF_CONFIG_DIR) + "/calibration/sim_camera.yaml").base_T_eye);
}

// The camera component publishes the written K and distortion as its camera_info (undistort off,
// so that it passes them on as they are).
TEST(CameraFile, TheCameraComponentReadsWhatIsWritten) {
  const auto dir = scratch("camera_file_camera");
  const cal::CameraFile f = calibrated();
  cal::save_camera_file((dir / "camera.yaml").string(), f, "written by a test");
  msg::CameraInfo ci;
  ASSERT_TRUE(camera_info_of(dir / "camera.yaml", dir, ci));
  EXPECT_EQ(ci.width(), 640u);
  for (int i = 0; i < 9; ++i)
    EXPECT_DOUBLE_EQ(ci.k()[static_cast<std::size_t>(i)], f.intrinsics.camera_matrix(i / 3, i % 3));
  ASSERT_EQ(ci.d().size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(ci.d()[static_cast<std::size_t>(i)], f.intrinsics.distortion[i]);
  const cal::CameraFile back = cal::load_camera_file((dir / "camera.yaml").string());
  EXPECT_EQ(back.intrinsics.camera_matrix, f.intrinsics.camera_matrix);
  EXPECT_EQ(back.intrinsics.distortion, f.intrinsics.distortion);
  ASSERT_TRUE(back.base_T_eye);
  EXPECT_TRUE(back.base_T_eye->isApprox(*f.base_T_eye, 1e-12));
}

// camera_fixed (the camera-fixed mode) publishes the written pose as eye_T_base.
TEST(CameraFile, CameraFixedReadsTheWrittenPose) {
  const auto dir = scratch("camera_file_fixed");
  const cal::CameraFile f = calibrated();
  cal::save_camera_file((dir / "camera.yaml").string(), f, "written by a test");
  Harness h("camera_fixed", "{extrinsics: " + (dir / "camera.yaml").string() + "}", 30);
  auto base = h.watch<msg::PoseStamped>("eye_T_base");
  h.activate();
  h.tick(Time{0});
  msg::PoseStamped p;
  ASSERT_TRUE(base.take_latest(p));
  EXPECT_TRUE(msgs::to_isometry(p.pose()).isApprox(f.base_T_eye->inverse(), 1e-9));
}

TEST(CameraFile, HostileFilesAreRefusedNamingTheKey) {
  const auto dir = scratch("camera_file_hostile");
  const auto error_of = [&](const std::string& text) {
    const std::string path = (dir / "bad.yaml").string();
    std::ofstream(path) << text;
    try {
      cal::load_camera_file(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string head = "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n";
  const std::string k = "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ ";
  EXPECT_NE(error_of("%YAML:1.0\n---\nimage_width: -3\n").find("image_width: expected a whole number"),
            std::string::npos)
      << error_of("%YAML:1.0\n---\nimage_width: -3\n");
  EXPECT_NE(error_of(head).find("camera_matrix: missing; expected an !!opencv-matrix"), std::string::npos)
      << error_of(head);
  EXPECT_NE(error_of(head + k + "0, 0, 319.5, 0, 600, 239.5, 0, 0, 1 ]\n").find("fx, fy > 0"), std::string::npos);
  EXPECT_NE(error_of(head + k + "600, 0, 9000, 0, 600, 239.5, 0, 0, 1 ]\n").find("principal point inside"),
            std::string::npos);
  EXPECT_NE(error_of(head + k + "600, 0, 319.5, 0, .nan, 239.5, 0, 0, 1 ]\n").find("expected finite numbers"),
            std::string::npos);
  EXPECT_NE(error_of("not: [yaml").find("bad.yaml"), std::string::npos);
  EXPECT_NE(error_of(head + k +
                     "600, 0, 319.5, 0, 600, 239.5, 0, 0, 1 ]\nbase_T_eye: !!opencv-matrix\n   rows: 4\n"
                     "   cols: 4\n   dt: d\n   data: [ 2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 ]\n")
                .find("base_T_eye: expected a rigid transform"),
            std::string::npos);
  // A stereo camera's rectification: both matrices or neither, a rotation, a 3x4 projection.
  const std::string good_k = head + k + "600, 0, 319.5, 0, 600, 239.5, 0, 0, 1 ]\n";
  const std::string r = "rectification_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ ";
  const std::string p = "projection_matrix: !!opencv-matrix\n   rows: 3\n   cols: 4\n   dt: d\n   data: [ ";
  EXPECT_NE(error_of(good_k + r + "1, 0, 0, 0, 1, 0, 0, 0, 1 ]\n").find("together, or neither"), std::string::npos);
  EXPECT_NE(
      error_of(good_k + r + "2, 0, 0, 0, 1, 0, 0, 0, 1 ]\n" + p + "600, 0, 320, 0, 0, 600, 240, 0, 0, 0, 1, 0 ]\n")
          .find("rectification_matrix: expected a 3x3 rotation"),
      std::string::npos);
  EXPECT_NE(error_of(good_k + r + "1, 0, 0, 0, 1, 0, 0, 0, 1 ]\n" + p + "0, 0, 320, 0, 0, 600, 240, 0, 0, 0, 1, 0 ]\n")
                .find("projection_matrix: expected 3x4"),
            std::string::npos);
  EXPECT_EQ(
      error_of(good_k + r + "1, 0, 0, 0, 1, 0, 0, 0, 1 ]\n" + p + "600, 0, 320, -36, 0, 600, 240, 0, 0, 0, 1, 0 ]\n"),
      "accepted");
  EXPECT_THROW(cal::load_camera_file((dir / "missing.yaml").string()), std::runtime_error);
}

}  // namespace wysiwyf::test
