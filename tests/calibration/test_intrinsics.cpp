// Camera intrinsics from simulated ChArUco views: the board rendered through a known camera (the
// shipped one perturbed by a seeded error, with lens distortion), blurred and noisy as a webcam's,
// detected and calibrated; the result against the truth, every view's error reported, and bad
// sets (too few views, a blurred board, a board too small in the image) refused with the reason.
#include <gtest/gtest.h>

#include <cstdio>

#include "calibration/board_view_sim.hpp"
#include "calibration/intrinsics_fit.hpp"
#include "calibration_truth.hpp"

namespace wysiwyf::test {

namespace cal = vision::calibration;

namespace {

std::vector<cal::BoardDetection> views(const cal::CharucoTarget& target, const cal::CameraIntrinsics& truth, int count,
                                       unsigned seed, const cal::ViewConditions& conditions = {}) {
  std::mt19937 rng(seed);
  const cal::BoardViewSim sim(target, truth);
  std::vector<cal::BoardDetection> out;
  for (const Eigen::Isometry3d& pose : cal::board_view_poses(target, truth, count, rng))
    out.push_back(
        cal::detect_board(sim.render(pose, conditions, rng), target, "view " + std::to_string(out.size() + 1)));
  return out;
}

}  // namespace

// 32 views of the A4 board (10 x 7 squares of 28 mm) through a distorting lens: focal lengths
// within 0.3 %, the principal point within 0.5 px; every view's error reported. The principal point
// is what needs the views (its sigma is 0.43 to 0.57 px at 16 views, 0.31 to 0.36 px at 32).
TEST(Intrinsics, RecoveredFromThirtyTwoViewsWithinThresholds) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  for (unsigned seed : {11u, 12u}) {
    const cal::CameraIntrinsics truth = perturbed_sim_camera(seed);
    const cal::IntrinsicsFit fit = cal::fit_intrinsics(views(target, truth, 32, seed), target);
    ASSERT_TRUE(fit.accepted) << cal::describe(fit, {});
    const cv::Matx33d &K = fit.camera.camera_matrix, &T = truth.camera_matrix;
    const double fx = std::abs(K(0, 0) / T(0, 0) - 1), fy = std::abs(K(1, 1) / T(1, 1) - 1);
    const double pp = std::hypot(K(0, 2) - T(0, 2), K(1, 2) - T(1, 2));
    EXPECT_LE(fx, 0.003) << cal::describe(fit, {});
    EXPECT_LE(fy, 0.003);
    EXPECT_LE(pp, 0.5) << cal::describe(fit, {});
    EXPECT_NEAR(fit.camera.distortion[0], truth.distortion[0], 0.01);
    ASSERT_EQ(fit.views.size(), 32u);
    for (const auto& v : fit.views) EXPECT_GT(v.rms, 0) << v.name << " has no error reported";
    std::printf("seed %u: focal error %.3f %% %.3f %%, principal point error %.3f px, rms %.3f px\n", seed, 100 * fx,
                100 * fy, pp, fit.rms);
  }
}

TEST(Intrinsics, TooFewViewsAreRefused) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  const cal::IntrinsicsFit fit = cal::fit_intrinsics(views(target, perturbed_sim_camera(3), 5, 3), target);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("5 usable views of 5; expected at least 10"), std::string::npos) << fit.refusal;
  EXPECT_FALSE(cal::fit_intrinsics({}, target).accepted);
}

// Out of focus (a 2 px blur): the board is still found, but its corners are not trusted.
TEST(Intrinsics, ABlurredBoardIsRefused) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  cal::ViewConditions blurred;
  blurred.blur_sigma = 2.0;
  const auto detections = views(target, perturbed_sim_camera(4), 12, 4, blurred);
  const cal::IntrinsicsFit fit = cal::fit_intrinsics(detections, target);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("blurred: focus the camera"), std::string::npos) << cal::describe(fit, {});
  int found = 0;
  for (const auto& v : fit.views) found += v.note.rfind("blurred: edges", 0) == 0 || v.note == "no board found";
  EXPECT_EQ(found, 12) << cal::describe(fit, {});
}

// A view with the board mostly out of the image is named and left out; the rest still calibrate.
TEST(Intrinsics, AViewWithTooLittleCoverageIsNamed) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  const cal::CameraIntrinsics truth = perturbed_sim_camera(5);
  auto detections = views(target, truth, 14, 5);
  Eigen::Isometry3d edge = Eigen::Isometry3d::Identity();
  edge.translation() = Eigen::Vector3d(-0.443, -0.1, 0.4);  // 5 cm of the board inside the image's left edge
  if (target.texture_y_flipped()) edge.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  std::mt19937 rng(5);
  detections.push_back(cal::detect_board(cal::BoardViewSim(target, truth).render(edge, {}, rng), target, "edge.png"));
  const cal::IntrinsicsFit fit = cal::fit_intrinsics(detections, target);
  ASSERT_EQ(fit.views.back().name, "edge.png");
  EXPECT_EQ(fit.views.back().note.rfind("too little coverage", 0), 0u) << cal::describe(fit, {});
  EXPECT_TRUE(fit.accepted) << cal::describe(fit, {});
  EXPECT_NE(cal::describe(fit, {}).find("edge.png"), std::string::npos);
}

// Views that keep the board in the middle of the image leave the corners' cells empty: refused,
// naming them.
TEST(Intrinsics, PoorCoverageOfTheImageIsRefused) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  const cal::CameraIntrinsics truth = perturbed_sim_camera(6);
  std::mt19937 rng(6);
  const cal::BoardViewSim sim(target, truth);
  std::vector<cal::BoardDetection> detections;
  for (int i = 0; i < 12; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() =
        Eigen::AngleAxisd(0.3 * std::sin(i), Eigen::Vector3d(std::cos(i), std::sin(i), 0)).toRotationMatrix() *
        (target.texture_y_flipped() ? Eigen::Matrix3d(Eigen::Vector3d(1, -1, -1).asDiagonal())
                                    : Eigen::Matrix3d::Identity());
    pose.translation() = Eigen::Vector3d(0, 0, 0.75) - pose.linear() * Eigen::Vector3d(0.14, 0.1, 0);
    detections.push_back(cal::detect_board(sim.render(pose, {}, rng), target, "centre " + std::to_string(i)));
  }
  const cal::IntrinsicsFit fit = cal::fit_intrinsics(detections, target);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("no corner in: top left"), std::string::npos) << cal::describe(fit, {});
}

}  // namespace wysiwyf::test
