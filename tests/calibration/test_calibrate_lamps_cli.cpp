// `wysiwyf calibrate lamps` as a lab runs it: the poses planned by camera-base-poses, an image of
// the lit lamps at each (the truth: the URDF's marker_* links moved by up to 2 mm, the camera 1 cm
// and 1 degree from its rough pose), the lamps written into a copy of the URDF that ArmModel loads;
// too few views refused, nothing written.
#include <gtest/gtest.h>

#include <random>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "arm_model/arm_model.hpp"
#include "calibrate_cli.hpp"
#include "calibration/camera_file.hpp"
#include "calibration/camera_model.hpp"
#include "calibration/flange_views_file.hpp"

namespace wysiwyf::test {
namespace {

namespace cal = vision::calibration;
namespace fs = std::filesystem;

const std::string kConfig = WYSIWYF_CONFIG_DIR;

TEST(CalibrateCli, LampsFromImagesIntoACopyOfTheUrdf) {
  const fs::path dir = scratch("cli_lamps");
  const CliRun planned = calibrate("camera-base-poses --camera " + kConfig + "/calibration/sim_camera.yaml" +
                                   " --home 0.344932,0.380005,-3.43618,0.346061,1.49034,3.11254 --count 30 --out " +
                                   (dir / "views.yaml").string());
  ASSERT_EQ(planned.status, 0) << planned.output;

  const robot::ArmModel arm(kConfig + "/robots/puma560.urdf", "dev");
  const robot::FrameId flange = arm.frame("flange");
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mm2(-0.002, 0.002);
  std::vector<Eigen::Vector3d> truth;
  for (int i = 0; i < 4; ++i)
    truth.push_back(
        (arm.fk(q0, flange).inverse() * arm.fk(q0, arm.frame("marker_" + std::to_string(i)))).translation() +
        Eigen::Vector3d(mm2(rng), mm2(rng), mm2(rng)));
  const cal::CameraFile camera = cal::load_camera_file(kConfig + "/calibration/sim_camera.yaml");
  const Eigen::Isometry3d base_T_eye = *camera.base_T_eye * Eigen::Translation3d(0.006, -0.008, 0.004) *
                                       Eigen::AngleAxisd(0.017, Eigen::Vector3d(1, 2, 3).normalized());
  std::normal_distribution<double> grey(0, 2);
  for (const auto& v : cal::load_flange_views((dir / "views.yaml").string(), 6)) {
    cv::Mat image(camera.intrinsics.size, CV_8UC1, cv::Scalar(60));
    for (int r = 0; r < image.rows; ++r)
      for (int c = 0; c < image.cols; ++c)
        image.at<std::uint8_t>(r, c) = cv::saturate_cast<std::uint8_t>(60 + grey(rng));
    const Eigen::Isometry3d eye_T_flange = base_T_eye.inverse() * arm.fk(v.joints, flange);
    for (const auto& p : truth) {
      const cv::Point2f px =
          cal::project(camera.intrinsics, eye_T_flange,
                       {cv::Point3f(p.cast<float>().x(), p.cast<float>().y(), p.cast<float>().z())})[0];
      cv::circle(image, cv::Point(cvRound(px.x * 16), cvRound(px.y * 16)), 3 * 16, cv::Scalar(255), cv::FILLED,
                 cv::LINE_AA, 4);
    }
    cv::imwrite(v.image, image);
  }
  const std::string lamps =
      "lamps --camera " + kConfig + "/calibration/sim_camera.yaml --views " + (dir / "views.yaml").string() + " --out ";
  const CliRun fitted = calibrate(lamps + (dir / "lamps.urdf").string());
  ASSERT_EQ(fitted.status, 0) << fitted.output;
  EXPECT_NE(fitted.output.find("marker_3:"), std::string::npos) << fitted.output;

  const robot::ArmModel found((dir / "lamps.urdf").string(), "dev");
  double worst = 0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d p =
        (found.fk(q0, found.frame("flange")).inverse() * found.fk(q0, found.frame("marker_" + std::to_string(i))))
            .translation();
    worst = std::max(worst, (p - truth[i]).norm());
  }
  std::printf("lamps from 30 images: the worst %.3f mm from the truth\n", worst * 1e3);
  EXPECT_LE(worst, 0.0005) << fitted.output;
  // The rest of the arm as it was: the plate's frame where the shipped URDF has it.
  EXPECT_TRUE(found.fk(q0, found.frame("dev")).isApprox(arm.fk(q0, arm.frame("dev")), 1e-9));

  const CliRun few = calibrate(lamps + (dir / "few.urdf").string() + " --min-views 40");
  EXPECT_EQ(few.status, 1) << few.output;
  EXPECT_NE(few.output.find("refused"), std::string::npos) << few.output;
  EXPECT_FALSE(fs::exists(dir / "few.urdf"));
}

}  // namespace
}  // namespace wysiwyf::test
