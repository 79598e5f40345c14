#pragma once
// Simulated views of a ChArUco board through a known camera, the truth the calibrations are
// tested and measured against: every image pixel (sampled 3 x 3 within it) is traced back through
// the camera's distortion onto the board's plane and takes the board texture's grey there; then a
// Gaussian blur (focus) and Gaussian noise (the sensor). Board poses that fill the image come from
// board_view_poses.
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "calibration/camera_model.hpp"
#include "calibration/charuco_target.hpp"

namespace wysiwyf::vision::calibration {

struct ViewConditions {
  double blur_sigma = 0.6;   // px, the lens's focus
  double noise_sigma = 2.0;  // grey levels per pixel
  int background = 110;      // grey around the board
};

class BoardViewSim {
 public:
  // Traces the camera's pixels once (they depend on the intrinsics only).
  BoardViewSim(const CharucoTarget& target, const CameraIntrinsics& camera);

  // The 8-bit grey image of the board at eye_T_board.
  cv::Mat render(const Eigen::Isometry3d& eye_T_board, const ViewConditions& conditions, std::mt19937& rng) const;

 private:
  const CharucoTarget& target_;
  CameraIntrinsics camera_;
  cv::Mat texture_;
  double texture_scale_ = 0;       // texture pixels per metre
  std::vector<cv::Point2f> rays_;  // undistorted normalised image coordinates of every sample
};

// A camera of the nominal one's model as one might really be (seeded): focal lengths off by up to
// 3 % (their ratio by 0.3 %), the principal point by up to 8 px, k1 in [-0.18, 0.02], k2 within
// 0.05, p1 and p2 within 0.001, k3 0.
CameraIntrinsics perturbed_camera(const CameraIntrinsics& nominal, unsigned seed);

// `count` board poses (seeded) that a calibration wants: the board 0.28 to 0.55 m away, turned 15
// to 45 degrees about varied axes, its centre spread over the image, every corner inside it.
std::vector<Eigen::Isometry3d> board_view_poses(const CharucoTarget& target, const CameraIntrinsics& camera, int count,
                                                std::mt19937& rng);

}  // namespace wysiwyf::vision::calibration
