#include "calibration/board_view_sim.hpp"

#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

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

std::vector<Eigen::Isometry3d> board_view_poses(const CharucoTarget& target, const CameraIntrinsics& camera, int count,
                                                std::mt19937& rng) {
  std::uniform_real_distribution<double> u01(0, 1);
  const Eigen::Vector3d centre(target.width() / 2, target.height() / 2, 0);
  const cv::Matx33d& K = camera.camera_matrix;
  std::vector<Eigen::Isometry3d> out;
  std::vector<cv::Point3f> outline{{0, 0, 0},
                                   {static_cast<float>(target.width()), 0, 0},
                                   {0, static_cast<float>(target.height()), 0},
                                   {static_cast<float>(target.width()), static_cast<float>(target.height()), 0}};
  for (int tries = 0; static_cast<int>(out.size()) < count && tries < 1000 * count; ++tries) {
    const double z = 0.28 + 0.27 * u01(rng);
    const double px = camera.size.width * (0.15 + 0.7 * u01(rng)), py = camera.size.height * (0.15 + 0.7 * u01(rng));
    const Eigen::Vector3d at(z * (px - K(0, 2)) / K(0, 0), z * (py - K(1, 2)) / K(1, 1), z);
    // Facing the camera so that the texture reads as printed (a y-up board turned over about x),
    // tilted about a random in-plane axis, spun about the view axis.
    const double axis = 2 * M_PI * u01(rng), tilt = (15 + 30 * u01(rng)) * M_PI / 180;
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(axis), std::sin(axis), 0)).toRotationMatrix() *
        Eigen::AngleAxisd((u01(rng) - 0.5) * M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        (target.texture_y_flipped() ? Eigen::Matrix3d(Eigen::Vector3d(1, -1, -1).asDiagonal())
                                    : Eigen::Matrix3d::Identity());
    Eigen::Isometry3d eye_T_board = Eigen::Isometry3d::Identity();
    eye_T_board.linear() = R;
    eye_T_board.translation() = at - R * centre;
    bool inside = true;
    for (const cv::Point2f& p : project(camera, eye_T_board, outline))
      inside = inside && p.x > 8 && p.y > 8 && p.x < camera.size.width - 8 && p.y < camera.size.height - 8;
    if (inside) out.push_back(eye_T_board);
  }
  return out;
}

}  // namespace wysiwyf::vision::calibration
