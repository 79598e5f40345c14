// camera_fixed (the paper's camera-fixed mode): eye_T_base from an OpenCV extrinsics file, in each
// of the forms calibration tools write, and eye_T_dev through the arm's kinematics, with the
// covariance carried to the device; a file that is not a calibration is a configuration error
// naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/core/persistence.hpp>

#include "frames/look_at.hpp"
#include "puma_model/puma_model.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {

namespace {

std::filesystem::path scratch() {
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / "camera_fixed";
  std::filesystem::create_directories(dir);
  return dir;
}

// camera_sim's default view.
const Eigen::Isometry3d kEyeTBase =
    vision::frames::look_at(Eigen::Vector3d(1.3, -0.5, 0.75), Eigen::Vector3d(0.55, 0.0, 0.35)).inverse();

cv::Mat to_cv(const Eigen::Matrix4d& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}

Eigen::Isometry3d received(Input<msg::PoseStamped>& in) {
  msg::PoseStamped p;
  EXPECT_TRUE(in.take_latest(p));
  return msgs::to_isometry(p.pose());
}

}  // namespace

TEST(CameraFixed, PublishesTheCalibratedPoseInEachFileForm) {
  const auto dir = scratch();
  cv::Mat R, rvec;
  cv::eigen2cv(Eigen::Matrix3d(kEyeTBase.linear()), R);
  cv::Rodrigues(R, rvec);
  const Eigen::Vector3d t = kEyeTBase.translation();
  {
    cv::FileStorage fs((dir / "rvec_tvec.yaml").string(), cv::FileStorage::WRITE);
    fs << "rvec" << rvec << "tvec" << cv::Mat(cv::Vec3d(t.x(), t.y(), t.z()));
  }
  {
    cv::FileStorage fs((dir / "eye_T_base.yaml").string(), cv::FileStorage::WRITE);
    fs << "eye_T_base" << to_cv(kEyeTBase.matrix());
  }
  {
    cv::FileStorage fs((dir / "base_T_eye.xml").string(), cv::FileStorage::WRITE);
    fs << "base_T_eye" << to_cv(kEyeTBase.inverse().matrix());
  }
  const robot::PumaModel model(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "flange");
  robot::Vector6d q;
  q << 0.37, 0.47, -3.17, 0.96, 1.62, 1.19;
  const Eigen::Isometry3d base_T_dev = model.fk(q, model.frame("dev"));
  for (const char* file : {"rvec_tvec.yaml", "eye_T_base.yaml", "base_T_eye.xml"}) {
    SCOPED_TRACE(file);
    Harness h("camera_fixed", "{extrinsics: " + (dir / file).string() + ", position_sigma: 0.002}", 30);
    auto joints = h.feed<msg::JointState>("joint_state");
    auto base = h.watch<msg::PoseStamped>("eye_T_base");
    auto dev = h.watch<msg::PoseStamped>("eye_T_dev");
    auto dev_cov = h.watch<msg::PoseWithCovariance>("eye_T_dev_covariance");
    h.activate();
    h.tick(Time{0});
    EXPECT_TRUE(kEyeTBase.isApprox(received(base), 1e-9));
    msg::PoseStamped none;
    EXPECT_FALSE(dev.take_latest(none)) << "eye_T_dev before any joint state";
    msg::JointState js;
    js.position().resize(6);
    for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = q[i];
    joints.write(js);
    h.tick(Time{33'333'333});
    EXPECT_TRUE((kEyeTBase * base_T_dev).isApprox(received(dev), 1e-9));
    // The plate ~0.8 m from the camera: a 2 mrad rotation error moves it by ~1.6 mm, on top of 2 mm.
    msg::PoseWithCovariance c;
    ASSERT_TRUE(dev_cov.take_latest(c));
    const double position_variance = c.covariance()[0] + c.covariance()[7] + c.covariance()[14];
    EXPECT_GT(position_variance, 3 * 0.002 * 0.002);
    EXPECT_LT(position_variance, 3 * 0.002 * 0.002 + 3 * std::pow(0.002 * 1.5, 2));
  }
}

// The shipped calibration of the display's simulated camera is its view (hardware/sim.yaml).
TEST(CameraFixed, TheShippedSimCalibrationIsTheSimulatedCamerasView) {
  const Eigen::Isometry3d eye_T_base =
      vision::frames::look_at(Eigen::Vector3d(1.6, -0.35, 0.7), Eigen::Vector3d(0.75, 0.0, 0.15)).inverse();
  Harness h("camera_fixed", "{extrinsics: calibration/sim_camera.yaml}", 30);
  auto base = h.watch<msg::PoseStamped>("eye_T_base");
  h.activate();
  h.tick(Time{0});
  const Eigen::Isometry3d got = received(base);
  EXPECT_LT((got.translation() - eye_T_base.translation()).norm(), 1e-6);
  EXPECT_LT(Eigen::Quaterniond(got.linear()).angularDistance(Eigen::Quaterniond(eye_T_base.linear())), 1e-6);
}

// With the camera's frames, the poses are for the newest frame: they carry its stamp, not the tick's.
TEST(CameraFixed, WithTheCamerasFramesThePosesCarryTheFramesStamp) {
  Harness h("camera_fixed", "{extrinsics: calibration/sim_camera.yaml}", 100);
  auto info = h.feed<msg::CameraInfo>("camera_info");
  auto joints = h.feed<msg::JointState>("joint_state");
  auto base = h.watch<msg::PoseStamped>("eye_T_base");
  auto dev = h.watch<msg::PoseStamped>("eye_T_dev");
  h.activate();
  h.tick(Time{10'000'000});
  msg::PoseStamped p;
  ASSERT_TRUE(base.take_latest(p));
  EXPECT_EQ(p.header().stamp_ns(), 10'000'000) << "no frame yet: the tick's time";
  msg::JointState zero;
  zero.position().assign(6, 0.0);
  joints.write(zero);
  msg::CameraInfo frame;
  fill_header(frame.header(), 13'500'000, 0, "eye");
  info.write(frame);
  h.tick(Time{20'000'000});
  ASSERT_TRUE(base.take_latest(p));
  EXPECT_EQ(p.header().stamp_ns(), 13'500'000);
  ASSERT_TRUE(dev.take_latest(p));
  EXPECT_EQ(p.header().stamp_ns(), 13'500'000);
}

TEST(CameraFixed, AFileThatIsNotACalibrationIsAConfigurationError) {
  const auto dir = scratch();
  {
    cv::FileStorage fs((dir / "not_a_rotation.yaml").string(), cv::FileStorage::WRITE);
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m(0, 0) = 2;
    fs << "eye_T_base" << to_cv(m);
  }
  {
    cv::FileStorage fs((dir / "intrinsics_only.yaml").string(), cv::FileStorage::WRITE);
    fs << "camera_matrix" << cv::Mat::eye(3, 3, CV_64F);
  }
  for (const auto& [file, expected] :
       std::vector<std::pair<std::string, std::string>>{{"not_a_rotation.yaml", "is not a rotation"},
                                                        {"intrinsics_only.yaml", "found none of rvec/tvec"},
                                                        {"missing.yaml", "does not exist"}}) {
    try {
      Harness h("camera_fixed", "{extrinsics: " + (dir / file).string() + "}", 30);
      ADD_FAILURE() << file << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("extrinsics"), std::string::npos) << e.what();
    }
  }
}

}  // namespace wysiwyf::test
