// A stereo pair's extrinsics and rectification from simulated views of the board seen by both
// cameras (each camera the shipped one perturbed by its own seeded error; the right one 6 cm to the
// right, turned a little), against the truth; the epipolar error after rectification reported; a
// pair whose right camera moved half-way, and too few pairs, refused with the reason.
#include <gtest/gtest.h>

#include <cstdio>

#include "calibration/board_view_sim.hpp"
#include "calibration/stereo_fit.hpp"
#include "calibration_truth.hpp"

namespace wysiwyf::test {

namespace cal = vision::calibration;

namespace {

struct Rig {
  cal::CameraIntrinsics left, right;
  Eigen::Isometry3d right_T_left = Eigen::Isometry3d::Identity();
};

Rig rig(unsigned seed) {
  Rig r{perturbed_sim_camera(seed), perturbed_sim_camera(seed + 100)};
  r.right_T_left.linear() =
      (Eigen::AngleAxisd(0.008, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(-0.004, Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(0.003, Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  r.right_T_left.translation() = Eigen::Vector3d(-0.06, 0.0004, -0.0007);  // the right camera 6 cm to the right
  return r;
}

// `count` board positions seen by both cameras; from `moved_from` on, the right camera is turned by
// a further `moved_by` rad (knocked).
void views(const Rig& r, int count, unsigned seed, std::vector<cal::BoardDetection>& left,
           std::vector<cal::BoardDetection>& right, int moved_from = 1 << 30, double moved_by = 0) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  std::mt19937 rng(seed);
  const cal::BoardViewSim sim_left(target, r.left), sim_right(target, r.right);
  const Eigen::Isometry3d knocked(Eigen::AngleAxisd(moved_by, Eigen::Vector3d::UnitX()));
  int i = 0;
  for (const Eigen::Isometry3d& left_T_board : cal::board_view_poses(target, r.left, count, rng)) {
    const Eigen::Isometry3d right_T_left = i >= moved_from ? knocked * r.right_T_left : r.right_T_left;
    const std::string name = "pair " + std::to_string(++i);
    left.push_back(cal::detect_board(sim_left.render(left_T_board, {}, rng), target, name));
    right.push_back(cal::detect_board(sim_right.render(right_T_left * left_T_board, {}, rng), target, name));
  }
}

}  // namespace

// 20 board positions: the baseline within 0.5 mm and the relative rotation within 0.05 deg of the
// truth; corners on one rectified row within 0.3 px RMS.
TEST(Stereo, ExtrinsicsAndRectificationFromTwentyPairs) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  for (unsigned seed : {21u, 22u}) {
    const Rig r = rig(seed);
    std::vector<cal::BoardDetection> left, right;
    views(r, 20, seed, left, right);
    const cal::StereoFit fit = cal::fit_stereo(left, right, target, r.left, r.right);
    ASSERT_TRUE(fit.accepted) << fit.refusal;
    const double t_err = (fit.right_T_left.translation() - r.right_T_left.translation()).norm();
    const double r_err =
        Eigen::AngleAxisd(fit.right_T_left.linear() * r.right_T_left.linear().transpose()).angle() * 180 / M_PI;
    std::printf(
        "seed %u: %d pairs, translation error %.3f mm, rotation error %.4f deg, epipolar RMS %.3f px "
        "(max %.3f px), reprojection RMS %.3f px\n",
        seed, fit.pairs_used, t_err * 1e3, r_err, fit.epipolar_rms, fit.epipolar_max, fit.rms);
    EXPECT_LE(t_err, 0.0005);
    EXPECT_LE(r_err, 0.05);
    EXPECT_LE(fit.epipolar_rms, 0.3);
    EXPECT_GE(fit.pairs_used, 18);
    // The rectified right camera sits -fx * baseline along x: P2(0,3).
    EXPECT_NEAR(-fit.P2(0, 3) / fit.P2(0, 0), r.right_T_left.translation().norm(), 0.0005);
  }
}

TEST(Stereo, ARightCameraKnockedHalfWayIsRefusedNamingTheWorstPairs) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  const Rig r = rig(23);
  std::vector<cal::BoardDetection> left, right;
  views(r, 20, 23, left, right, 10, 0.3 * M_PI / 180);  // 0.3 deg after pair 10
  const cal::StereoFit fit = cal::fit_stereo(left, right, target, r.left, r.right);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("epipolar error"), std::string::npos) << fit.refusal;
  EXPECT_NE(fit.refusal.find("worst pairs: pair "), std::string::npos) << fit.refusal;
  std::printf("refused: %s\n", fit.refusal.c_str());
}

TEST(Stereo, TooFewPairsOrUnmatchedListsAreRefused) {
  const cal::CharucoTarget target(cal::CharucoSpec{});
  const Rig r = rig(24);
  std::vector<cal::BoardDetection> left, right;
  views(r, 5, 24, left, right);
  cal::StereoFit fit = cal::fit_stereo(left, right, target, r.left, r.right);
  EXPECT_FALSE(fit.accepted);
  EXPECT_NE(fit.refusal.find("usable pairs of 5"), std::string::npos) << fit.refusal;
  right.pop_back();
  fit = cal::fit_stereo(left, right, target, r.left, r.right);
  EXPECT_NE(fit.refusal.find("5 left views and 4 right views"), std::string::npos) << fit.refusal;
}

}  // namespace wysiwyf::test
