#include "calibration/board_view_sim.hpp"

#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "calibration/board_placement.hpp"

namespace wysiwyf::vision::calibration {

namespace {

constexpr int kSamples = 3;            // per pixel and axis
constexpr int kPixelsPerSquare = 120;  // board texture

}  // namespace

BoardViewSim::BoardViewSim(const CharucoTarget& target, const CameraIntrinsics& camera)
    : target_(target), camera_(camera) {
  texture_ = target.texture(kPixelsPerSquare);
  texture_scale_ = kPixelsPerSquare / target.spec().square;
  const int w = camera.size.width * kSamples, h = camera.size.height * kSamples;
  std::vector<cv::Point2f> samples;
  samples.reserve(static_cast<std::size_t>(w) * h);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)  // sample centres within pixel (u / k, v / k), pixel centres at integers
      samples.emplace_back((u + 0.5f) / kSamples - 0.5f, (v + 0.5f) / kSamples - 0.5f);
  cv::undistortPoints(samples, rays_, cv::Mat(camera.camera_matrix), cv::Mat(camera.distortion), cv::noArray(),
                      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 40, 1e-12));
}

cv::Mat BoardViewSim::render(const Eigen::Isometry3d& eye_T_board, const ViewConditions& c, std::mt19937& rng) const {
  const int w = camera_.size.width * kSamples, h = camera_.size.height * kSamples;
  const Eigen::Isometry3d board_T_eye = eye_T_board.inverse();
  const Eigen::Matrix3d R = board_T_eye.linear();
  const Eigen::Vector3d o = board_T_eye.translation();
  cv::Mat map_x(h, w, CV_32FC1), map_y(h, w, CV_32FC1);
  const double rows = texture_.rows;
  const bool flipped = target_.texture_y_flipped();
  for (int i = 0; i < w * h; ++i) {
    const Eigen::Vector3d d =
        R * Eigen::Vector3d(rays_[static_cast<std::size_t>(i)].x, rays_[static_cast<std::size_t>(i)].y, 1.0);
    float x = -1e6f, y = -1e6f;  // outside the texture: the background
    if (std::abs(d.z()) > 1e-12) {
      const double t = -o.z() / d.z();
      if (t > 0) {
        const Eigen::Vector3d p = o + t * d;
        // Texture pixel j covers [j, j+1) texture units; remap samples pixel centres at integers.
        x = static_cast<float>(p.x() * texture_scale_ - 0.5);
        y = static_cast<float>((flipped ? rows - p.y() * texture_scale_ : p.y() * texture_scale_) - 0.5);
      }
    }
    map_x.at<float>(i) = x, map_y.at<float>(i) = y;
  }
  cv::Mat fine, image;
  cv::remap(texture_, fine, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(c.background));
  cv::resize(fine, image, camera_.size, 0, 0, cv::INTER_AREA);
  cv::Mat grey;
  image.convertTo(grey, CV_32F);
  if (c.blur_sigma > 0) cv::GaussianBlur(grey, grey, cv::Size(), c.blur_sigma);
  if (c.noise_sigma > 0) {
    std::normal_distribution<float> normal(0.0f, static_cast<float>(c.noise_sigma));
    for (auto it = grey.begin<float>(); it != grey.end<float>(); ++it) *it += normal(rng);
  }
  grey.convertTo(image, CV_8U);
  return image;
}

CameraIntrinsics perturbed_camera(const CameraIntrinsics& nominal, unsigned seed) {
  CameraIntrinsics cam = nominal;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  cam.camera_matrix(0, 0) *= 1 + 0.03 * u(rng);
  cam.camera_matrix(1, 1) = cam.camera_matrix(0, 0) * (1 + 0.003 * u(rng));
  cam.camera_matrix(0, 2) += 8 * u(rng);
  cam.camera_matrix(1, 2) += 8 * u(rng);
  const double k1 = -0.08 + 0.1 * u(rng), k2 = 0.05 * u(rng), p1 = 0.001 * u(rng), p2 = 0.001 * u(rng);
  cam.distortion = {k1, k2, p1, p2, 0};
  return cam;
}

std::vector<Eigen::Isometry3d> board_view_poses(const CharucoTarget& target, const CameraIntrinsics& camera, int count,
                                                std::mt19937& rng) {
  PlacementRanges ranges;
  ranges.near = 0.28, ranges.far = 0.55, ranges.min_tilt = 15, ranges.max_tilt = 45;
  const auto w = static_cast<float>(target.width()), h = static_cast<float>(target.height());
  const std::vector<cv::Point3f> outline{{0, 0, 0}, {w, 0, 0}, {0, h, 0}, {w, h, 0}};
  std::vector<Eigen::Isometry3d> out;
  for (int tries = 0; static_cast<int>(out.size()) < count && tries < 1000 * count; ++tries) {
    const Eigen::Isometry3d pose = eye_T_board(target, camera, random_placement(camera, ranges, rng));
    if (inside_image(camera, pose, outline, 8)) out.push_back(pose);
  }
  return out;
}

}  // namespace wysiwyf::vision::calibration
