#include "plate_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wysiwyf::vision {

namespace {

// The filter's process noise: the camera's motion, plus the device's when the device is in the
// state (independent accelerations: the densities add).
EkfNoise filter_noise(const TrackerSettings& s) {
  EkfNoise n = s.noise;
  if (s.device_motion == DeviceMotion::kState) {
    n.accel = std::hypot(n.accel, s.device_accel);
    n.angular_accel = std::hypot(n.angular_accel, s.device_angular_accel);
  }
  return n;
}

}  // namespace

PlateTracker::PlateTracker(PlateMarkers plate, TrackerSettings settings)
    : plate_(std::move(plate)), s_(std::move(settings)), detector_(s_.detector), ekf_(filter_noise(s_)) {}

const FrameResult& PlateTracker::process(const cv::Mat& image, PixelLayout layout, std::int64_t stamp_ns,
                                         const Eigen::Isometry3d& base_T_dev, const CameraModel& camera) {
  result_.acquired = false;
  result_.blobs = result_.rejected = 0;
  result_.matched.clear();
  result_.windows.clear();
  result_.rms_px = 0;
  base_T_dev_ = base_T_dev;
  if (s_.device_motion == DeviceMotion::kInput) {
    x_T_dev_ = base_T_dev;
    x_T_base_.setIdentity();
  } else {
    x_T_dev_.setIdentity();
    x_T_base_ = base_T_dev.inverse();
  }
  const double dt = have_stamp_ ? static_cast<double>(stamp_ns - last_stamp_) * 1e-9 : 0.0;
  last_stamp_ = stamp_ns, have_stamp_ = true;
  if (state_ != TrackState::kLost) {
    ekf_.predict(dt);
    track(image, layout, camera);
  } else {
    acquire(image, layout, camera);
  }
  if (has_estimate()) last_eye_T_base_ = eye_T_base(), have_last_ = true;
  result_.state = state_;
  return result_;
}

bool PlateTracker::predict_lamp(int i, const CameraModel& camera, PoseEkf::Prediction& out) const {
  const Eigen::Isometry3d eye_T_dev = ekf_.pose() * x_T_dev_;
  const Eigen::Vector3d& dev_p = plate_.dev_p[static_cast<std::size_t>(i)];
  const Eigen::Vector3d centre = eye_T_dev * dev_p, normal = eye_T_dev.linear() * plate_.dev_normal;
  if (centre.z() <= 0 || PlateMarkers::facing(centre, normal) < 0.05) return false;  // the plate's edge or back
  return ekf_.predict_pixel(x_T_dev_ * dev_p, plate_.dome_offset(centre, normal), camera, out);
}

void PlateTracker::track(const cv::Mat& image, PixelLayout layout, const CameraModel& camera) {
  accepted_.clear(), accepted_pixels_.clear(), accepted_ids_.clear();
  for (int i = 0; i < 4; ++i) {
    PoseEkf::Prediction pred;
    if (!predict_lamp(i, camera, pred)) continue;
    const double lamp_px = camera.fx() * plate_.lamp_radius / pred.depth;
    const double sigma = std::sqrt(std::max(pred.S(0, 0), pred.S(1, 1)));
    const double reach = std::ceil(3 * sigma + 1.5 * lamp_px + 2);
    const int half =
        static_cast<int>(std::clamp(reach, static_cast<double>(s_.min_window), static_cast<double>(s_.max_window)));
    const Eigen::Vector2d centre = camera.distort(pred.pixel);
    if (!centre.allFinite() || std::abs(centre.x()) > 1e6 || std::abs(centre.y()) > 1e6) continue;
    const cv::Rect window(static_cast<int>(std::lround(centre.x())) - half,
                          static_cast<int>(std::lround(centre.y())) - half, 2 * half + 1, 2 * half + 1);
    result_.windows.push_back(window);
    blobs_.clear();
    if (!detector_.detect_in(image, layout, window, blobs_)) continue;
    result_.blobs += static_cast<int>(blobs_.size());
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    Eigen::Vector2d best_ideal;
    for (int b = 0; b < static_cast<int>(blobs_.size()); ++b) {
      const Eigen::Vector2d ideal =
          camera.undistort({blobs_[static_cast<std::size_t>(b)].u, blobs_[static_cast<std::size_t>(b)].v});
      const double d2 = PoseEkf::mahalanobis2(pred, ideal);
      if (d2 < best_d2) best = b, best_d2 = d2, best_ideal = ideal;
    }
    if (best >= 0 && best_d2 <= s_.gate) {
      accepted_.push_back(pred);
      accepted_pixels_.push_back(best_ideal);
      accepted_ids_.push_back(i);
      result_.matched.push_back(
          MatchedLamp{i, blobs_[static_cast<std::size_t>(best)].u, blobs_[static_cast<std::size_t>(best)].v});
      result_.rejected += static_cast<int>(blobs_.size()) - 1;
    } else {
      result_.rejected += static_cast<int>(blobs_.size());
    }
  }
  if (static_cast<int>(accepted_.size()) >= s_.min_markers) {
    ekf_.update(accepted_, accepted_pixels_);
    result_.frames_without_fix = 0;
    result_.rms_px = reprojection_rms(camera);
    state_ = TrackState::kTracking;
    return;
  }
  ++result_.frames_without_fix;
  state_ = result_.frames_without_fix >= s_.lost_after ? TrackState::kLost : TrackState::kCoasting;
}

void PlateTracker::acquire(const cv::Mat& image, PixelLayout layout, const CameraModel& camera) {
  blobs_.clear();
  detector_.detect_all(image, layout, blobs_);
  result_.blobs = static_cast<int>(blobs_.size());
  std::vector<Blob> ideal = blobs_;
  for (auto& b : ideal) {
    const Eigen::Vector2d p = camera.undistort({b.u, b.v});
    b.u = p.x(), b.v = p.y();
  }
  // Which of the near-equal fits: the one nearest the last estimate (the camera moves little
  // while the plate is lost, and the device's motion is known), else the one that has the
  // base's up axis pointing up in the image.
  const Eigen::Isometry3d expected_eye_T_dev = last_eye_T_base_ * base_T_dev_;
  const Eigen::Matrix3d dev_R_base = base_T_dev_.linear().transpose();
  const Eigen::Vector3d up = s_.up_in_base.normalized();
  auto cost = [&](const Eigen::Isometry3d& eye_T_dev, double rms) {
    if (have_last_) {
      const double angle = Eigen::AngleAxisd(expected_eye_T_dev.linear().transpose() * eye_T_dev.linear()).angle();
      return angle + (eye_T_dev.translation() - expected_eye_T_dev.translation()).norm() / 0.1 + 0.01 * rms;
    }
    const Eigen::Vector3d up_in_eye = eye_T_dev.linear() * dev_R_base * up;
    return (1.0 + up_in_eye.y()) + rms;  // image y points down: 0 when up is straight up
  };
  const auto fix = acquire_plate(ideal, plate_, camera, cost, s_.acquisition);
  if (!fix) {
    if (acquire_from_guess(camera)) return;
    ++result_.frames_without_fix;
    return;
  }
  const Eigen::Isometry3d dev_T_x = x_T_dev_.inverse();
  PoseEkf::Matrix6d dev_cov = PoseEkf::Matrix6d::Zero();
  dev_cov.diagonal() << Eigen::Vector3d::Constant(s_.start_sigma_m * s_.start_sigma_m),
      Eigen::Vector3d::Constant(s_.start_sigma_rad * s_.start_sigma_rad);
  ekf_.reset(fix->eye_T_dev * dev_T_x, frames::compose_covariance(dev_cov, fix->eye_T_dev, dev_T_x),
             s_.start_velocity_sigma, s_.start_angular_sigma);
  // The fix's lamps are this image's measurements too.
  accepted_.clear(), accepted_pixels_.clear(), accepted_ids_.clear();
  for (int i = 0; i < 4; ++i) {
    PoseEkf::Prediction pred;
    if (!predict_lamp(i, camera, pred)) continue;
    const auto blob = static_cast<std::size_t>(fix->blob_of_marker[static_cast<std::size_t>(i)]);
    accepted_.push_back(pred);
    accepted_pixels_.emplace_back(ideal[blob].u, ideal[blob].v);
    accepted_ids_.push_back(i);
    result_.matched.push_back(MatchedLamp{i, blobs_[blob].u, blobs_[blob].v});
  }
  ekf_.update(accepted_, accepted_pixels_);
  result_.rms_px = reprojection_rms(camera);
  result_.acquired = true;
  result_.frames_without_fix = 0;
  state_ = TrackState::kTracking;
}

bool PlateTracker::acquire_from_guess(const CameraModel& camera) {
  if (!have_last_ && !s_.has_prior) return false;
  const Eigen::Isometry3d guess = have_last_ ? last_eye_T_base_ : s_.prior_eye_T_base;
  PoseEkf::Matrix6d cov = PoseEkf::Matrix6d::Zero();
  cov.diagonal() << Eigen::Vector3d::Constant(s_.prior_sigma_m * s_.prior_sigma_m),
      Eigen::Vector3d::Constant(s_.prior_sigma_rad * s_.prior_sigma_rad);
  // The guess is uncertain about the camera: its errors are those of eye_T_base, carried to x.
  const Eigen::Isometry3d base_T_x = x_T_base_.inverse();
  ekf_.reset(guess * base_T_x, frames::compose_covariance(cov, guess, base_T_x), s_.start_velocity_sigma,
             s_.start_angular_sigma);
  match_blobs(camera);
  if (static_cast<int>(accepted_.size()) < std::max(2, s_.min_markers)) return false;
  ekf_.update(accepted_, accepted_pixels_);
  result_.rms_px = reprojection_rms(camera);
  result_.acquired = true;
  result_.frames_without_fix = 0;
  state_ = TrackState::kTracking;
  return true;
}

void PlateTracker::match_blobs(const CameraModel& camera) {
  accepted_.clear(), accepted_pixels_.clear(), accepted_ids_.clear();
  result_.matched.clear();
  std::vector<bool> taken(blobs_.size(), false);
  for (int i = 0; i < 4; ++i) {
    PoseEkf::Prediction pred;
    if (!predict_lamp(i, camera, pred)) continue;
    int best = -1;
    double best_d2 = s_.gate;
    Eigen::Vector2d best_ideal;
    for (std::size_t b = 0; b < blobs_.size(); ++b) {
      const Eigen::Vector2d ideal = camera.undistort({blobs_[b].u, blobs_[b].v});
      const double d2 = PoseEkf::mahalanobis2(pred, ideal);
      if (d2 <= best_d2) best = static_cast<int>(b), best_d2 = d2, best_ideal = ideal;
    }
    if (best < 0 || taken[static_cast<std::size_t>(best)]) continue;  // none, or already the match of another lamp
    taken[static_cast<std::size_t>(best)] = true;
    accepted_.push_back(pred);
    accepted_pixels_.push_back(best_ideal);
    accepted_ids_.push_back(i);
    result_.matched.push_back(
        MatchedLamp{i, blobs_[static_cast<std::size_t>(best)].u, blobs_[static_cast<std::size_t>(best)].v});
  }
  result_.rejected = static_cast<int>(blobs_.size() - accepted_.size());
}

double PlateTracker::reprojection_rms(const CameraModel& camera) const {
  double sum = 0;
  int n = 0;
  for (std::size_t k = 0; k < accepted_ids_.size(); ++k) {
    PoseEkf::Prediction pred;
    if (!predict_lamp(accepted_ids_[k], camera, pred)) continue;
    sum += (pred.pixel - accepted_pixels_[k]).squaredNorm(), ++n;
  }
  return n ? std::sqrt(sum / n) : 0.0;
}

}  // namespace wysiwyf::vision
