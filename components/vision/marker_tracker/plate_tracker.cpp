#include "plate_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wysiwyf::vision {

namespace {

// The filter's process noise: the camera's motion, plus the device's when the device is in the
// state (independent accelerations: the densities add; the device moves at sustained speeds, so
// that state's velocity persists).
EkfNoise filter_noise(const TrackerSettings& s) {
  EkfNoise n = s.noise;
  if (s.device_motion == DeviceMotion::kState) {
    n.accel = std::hypot(n.accel, s.device_accel);
    n.angular_accel = std::hypot(n.angular_accel, s.device_angular_accel);
    n.velocity_time = 0;
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
  result_.refused = Refusal::kNone;
  result_.jump = CameraMotion{};
  result_.since_trusted_s = 0;
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
    if (have_trusted_) ekf_.predict(dt);  // what the filter expects while the lamps are out of sight
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
  matcher_.clear();
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
    matcher_.predict(i, pred);
    blobs_.clear();
    if (!detector_.detect_in(image, layout, window, blobs_)) continue;
    for (const Blob& b : blobs_) matcher_.add_blob(b, camera.undistort({b.u, b.v}));
  }
  result_.blobs = matcher_.blobs();
  if (match_lamps() && static_cast<int>(accepted_.size()) >= s_.min_markers) {
    const PoseEkf predicted = ekf_;
    ekf_.update(accepted_, accepted_pixels_);
    if (admit()) {
      result_.frames_without_fix = 0;
      result_.rms_px = reprojection_rms(camera);
      state_ = TrackState::kTracking;
      return;
    }
    ekf_ = predicted;  // the refused update never happened
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
  // Which of the near-equal fits: the arm's joints say where the plate is in the base frame, so
  // each fit says where the camera is. A fit that moves the camera farther than it can go since
  // the last trusted estimate is no fit; of the others, the one nearest the last estimate (the
  // camera moves little while the plate is lost), else nearest the set-up's prior pose, else
  // the one that has the base's up axis pointing up in the image.
  const Eigen::Isometry3d dev_T_base = base_T_dev_.inverse();
  const bool have_reference = have_last_ || s_.has_prior;
  const Eigen::Isometry3d expected_eye_T_dev = (have_last_ ? last_eye_T_base_ : s_.prior_eye_T_base) * base_T_dev_;
  const Eigen::Matrix3d dev_R_base = base_T_dev_.linear().transpose();
  const Eigen::Vector3d up = s_.up_in_base.normalized();
  const double since_trusted = static_cast<double>(last_stamp_ - trusted_stamp_) * 1e-9;
  int impossible = 0;
  CameraMotion nearest_impossible{std::numeric_limits<double>::infinity(), 0};
  auto cost = [&](const Eigen::Isometry3d& eye_T_dev, double rms) {
    if (have_trusted_) {
      const CameraMotion jump = CameraMotion::between(trusted_eye_T_base_, eye_T_dev * dev_T_base);
      if (!jump.possible(since_trusted, s_.motion)) {
        if (jump.distance_m < nearest_impossible.distance_m) nearest_impossible = jump;
        ++impossible;
        return std::numeric_limits<double>::infinity();
      }
    }
    if (have_reference) {
      const double angle = Eigen::AngleAxisd(expected_eye_T_dev.linear().transpose() * eye_T_dev.linear()).angle();
      return angle + (eye_T_dev.translation() - expected_eye_T_dev.translation()).norm() / 0.1 + 0.01 * rms;
    }
    const Eigen::Vector3d up_in_eye = eye_T_dev.linear() * dev_R_base * up;
    return (1.0 + up_in_eye.y()) + rms;  // image y points down: 0 when up is straight up
  };
  const auto fix = acquire_plate(ideal, plate_, camera, cost, s_.acquisition);
  if (!fix) {
    if (acquire_from_guess(camera)) return;
    if (impossible > 0 && result_.refused == Refusal::kNone) {
      result_.jump = nearest_impossible, result_.since_trusted_s = since_trusted;
      refuse(Refusal::kJump);
    }
    ++result_.frames_without_fix;
    return;
  }
  const PoseEkf before = ekf_;
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
  if (!admit()) {
    ekf_ = before;  // still lost: the next image starts from the filter's own prediction
    ++result_.frames_without_fix;
    return;
  }
  result_.rms_px = reprojection_rms(camera);
  result_.acquired = true;
  result_.frames_without_fix = 0;
  state_ = TrackState::kTracking;
}

bool PlateTracker::acquire_from_guess(const CameraModel& camera) {
  if (!have_last_ && !s_.has_prior) return false;
  const PoseEkf before = ekf_;
  PoseEkf::Matrix6d cov = PoseEkf::Matrix6d::Zero();
  cov.diagonal() << Eigen::Vector3d::Constant(s_.prior_sigma_m * s_.prior_sigma_m),
      Eigen::Vector3d::Constant(s_.prior_sigma_rad * s_.prior_sigma_rad);
  // The guess is uncertain about the camera: its errors are those of eye_T_base, carried to x.
  const Eigen::Isometry3d base_T_x = x_T_base_.inverse();
  // With the device's motion as a known input, the filter's own prediction of the camera first,
  // as it is: lamps that were only too dim to see are where it expects them, and it goes on as
  // if it had never lost them. Then the same prediction as uncertain as the prior more, its
  // velocities kept (fresh ones, unseen along the directions that two lamps do not pin, would
  // let the pose wander there). Otherwise the last estimate, or the prior, from rest.
  const bool resume = have_trusted_ && s_.device_motion == DeviceMotion::kInput;
  for (int attempt = resume ? 0 : 1; attempt < 2; ++attempt) {
    ekf_ = before;
    if (resume && attempt == 1) {
      ekf_.widen_pose(frames::compose_covariance(cov, ekf_.pose(), base_T_x));
    } else if (!resume) {
      const Eigen::Isometry3d guess = have_last_ ? last_eye_T_base_ : s_.prior_eye_T_base;
      ekf_.reset(guess * base_T_x, frames::compose_covariance(cov, guess, base_T_x), s_.start_velocity_sigma,
                 s_.start_angular_sigma);
    }
    matcher_.clear();
    for (const Blob& b : blobs_) matcher_.add_blob(b, camera.undistort({b.u, b.v}));
    for (int i = 0; i < 4; ++i) {
      PoseEkf::Prediction pred;
      if (predict_lamp(i, camera, pred)) matcher_.predict(i, pred);
    }
    if (!match_lamps() || static_cast<int>(accepted_.size()) < std::max(2, s_.min_markers)) continue;
    ekf_.update(accepted_, accepted_pixels_);
    if (!admit()) continue;
    result_.refused = Refusal::kNone;  // an earlier attempt's refusal no longer stands
    result_.rms_px = reprojection_rms(camera);
    result_.acquired = true;
    result_.frames_without_fix = 0;
    state_ = TrackState::kTracking;
    return true;
  }
  ekf_ = before;  // still lost: the next image starts from the same prediction
  result_.matched.clear();
  return false;
}

bool PlateTracker::match_lamps() {
  accepted_.clear(), accepted_pixels_.clear(), accepted_ids_.clear();
  result_.matched.clear();
  const LampMatch m = matcher_.solve(ekf_, s_.gate, s_.ambiguity);
  result_.rejected = matcher_.blobs() - m.matched;
  if (m.ambiguous) {
    refuse(Refusal::kAmbiguous);
    return false;
  }
  for (int i = 0; i < 4; ++i) {
    const int b = m.blob_of_lamp[static_cast<std::size_t>(i)];
    if (b < 0) continue;
    accepted_.push_back(matcher_.prediction(i));
    accepted_pixels_.push_back(matcher_.ideal(b));
    accepted_ids_.push_back(i);
    result_.matched.push_back(MatchedLamp{i, matcher_.blob(b).u, matcher_.blob(b).v});
  }
  return true;
}

bool PlateTracker::admit() {
  const Eigen::Isometry3d estimate = eye_T_base();
  if (have_trusted_) {
    const double since = static_cast<double>(last_stamp_ - trusted_stamp_) * 1e-9;
    const CameraMotion jump = CameraMotion::between(trusted_eye_T_base_, estimate);
    if (!jump.possible(since, s_.motion)) {
      result_.jump = jump, result_.since_trusted_s = since;
      refuse(Refusal::kJump);
      return false;
    }
  }
  trusted_eye_T_base_ = estimate, trusted_stamp_ = last_stamp_, have_trusted_ = true;
  return true;
}

void PlateTracker::refuse(Refusal why) {
  result_.refused = why;
  result_.matched.clear();  // none of this image's lamps were used
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
