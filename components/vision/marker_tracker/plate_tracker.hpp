#pragma once
// The tracking loop of the marker tracker, without ports: per image, predict the filter, look
// for each lamp in a search window around its predicted pixel, match the blob nearest in
// Mahalanobis distance (refusing those beyond the chi-square gate), update; after `lost_after`
// images with fewer than `min_markers` lamps declare the plate lost and search the whole frame
// until a PnP fix restarts the filter (or, with fewer than four lamps in view, until enough of
// them appear where the last estimate or the set-up's prior pose predicts them).
//
// No estimate moves the camera farther than it can go (motion_gate.hpp): an update, a PnP fix or
// a fix from the last estimate that would is refused and said so (FrameResult::refused). Blobs
// are given to lamps all together (lamp_matcher.hpp), and an image whose blobs could be more
// than one set of lamps is not used. Among PnP's near-equal fits (the coplanar lamps' two-fold
// ambiguity, sharpest face-on and edge-on) the arm's kinematics choose: base_T_dev is known, so
// each fit says where the camera is, and the one nearest where it was (or the prior) wins.
//
// The filter's state (paper section 5.1):
//   DeviceMotion::kInput  eye_T_base. The device's motion base_T_dev (joints + robot model) is a
//                         known input: lamp i is seen at eye_T_base * base_T_dev * dev_p_i. A
//                         still camera is a still state, whatever the robot does.
//   DeviceMotion::kState  eye_T_dev with a constant-velocity model (the paper's first
//                         prototype); eye_T_base = eye_T_dev * dev_T_base. Every robot motion is
//                         something the filter must follow, and the background shakes.
#include <opencv2/core.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "camera_model.hpp"
#include "bright_blobs/blob_detector.hpp"
#include "lamp_matcher.hpp"
#include "motion_gate.hpp"
#include "plate_acquisition.hpp"
#include "plate_markers.hpp"
#include "frames/pose_covariance.hpp"
#include "pose_ekf.hpp"

namespace wysiwyf::vision {

enum class DeviceMotion { kInput, kState };
enum class TrackState { kLost, kTracking, kCoasting };
// Why an image's fix was not used: none refused; it would move the camera farther than it can go
// (kJump); its blobs could be more than one set of lamps (kAmbiguous).
enum class Refusal { kNone, kJump, kAmbiguous };

struct TrackerSettings {
  DeviceMotion device_motion = DeviceMotion::kInput;
  PoseEkf::Noise noise;  // the camera's motion and the centroids' noise
  // kState only: the device's motion, which that filter must absorb as process noise too.
  double device_accel = 1.0, device_angular_accel = 2.0;
  double gate = 13.8;   // chi-square, 2 degrees of freedom (99.9 %)
  int min_markers = 2;  // lamps an image needs to update the filter
  int lost_after = 5;   // images without enough lamps before the plate is lost
  int min_window = 10;  // search window half size, px
  int max_window = 80;
  Eigen::Vector3d up_in_base = Eigen::Vector3d::UnitZ();  // appears up in the image (first fix)
  double start_sigma_m = 0.01, start_sigma_rad = 0.01;    // the fix's uncertainty, in dev
  // Where the camera is thought to be before any fix (the set-up's rough calibration), and how
  // well: lets the filter start from fewer than four lamps. has_prior false: four are needed.
  bool has_prior = false;
  Eigen::Isometry3d prior_eye_T_base = Eigen::Isometry3d::Identity();
  double prior_sigma_m = 0.02, prior_sigma_rad = 0.02;
  double start_velocity_sigma = 0.3, start_angular_sigma = 1.0;
  MotionLimits motion;  // how fast the camera can move: no estimate jumps farther
  // Another assignment of blobs to lamps whose joint squared Mahalanobis distance is within this
  // of the best one's (a likelihood ratio above e^-2) is as plausible: the image is not used.
  double ambiguity = 4.0;
  AcquisitionSettings acquisition;
  BlobDetector::Settings detector;
};

struct MatchedLamp {
  int id = 0;
  double u = 0, v = 0;  // measured, image pixels
};

struct FrameResult {
  TrackState state = TrackState::kLost;
  bool acquired = false;  // this image restarted the filter from a PnP fix
  int blobs = 0, rejected = 0;
  std::vector<MatchedLamp> matched;
  std::vector<cv::Rect> windows;
  double rms_px = 0;
  int frames_without_fix = 0;
  Refusal refused = Refusal::kNone;
  CameraMotion jump;           // kJump: how far the refused estimate would have moved the camera
  double since_trusted_s = 0;  // kJump: in this long since the last estimate the tracker trusted
};

class PlateTracker {
 public:
  PlateTracker(PlateMarkers plate, TrackerSettings settings);

  const FrameResult& process(const cv::Mat& image, PixelLayout layout, std::int64_t stamp_ns,
                             const Eigen::Isometry3d& base_T_dev, const CameraModel& camera);

  bool has_estimate() const { return state_ != TrackState::kLost; }
  // At the last image (valid while has_estimate()).
  Eigen::Isometry3d eye_T_base() const { return ekf_.pose() * x_T_base_; }
  Eigen::Isometry3d eye_T_dev() const { return ekf_.pose() * x_T_dev_; }
  PoseEkf::Matrix6d eye_T_base_covariance() const {
    return frames::compose_covariance(ekf_.pose_covariance(), ekf_.pose(), x_T_base_);
  }
  PoseEkf::Matrix6d eye_T_dev_covariance() const {
    return frames::compose_covariance(ekf_.pose_covariance(), ekf_.pose(), x_T_dev_);
  }
  const PoseEkf& filter() const { return ekf_; }
  const TrackerSettings& settings() const { return s_; }

 private:
  void track(const cv::Mat& image, PixelLayout layout, const CameraModel& camera);
  void acquire(const cv::Mat& image, PixelLayout layout, const CameraModel& camera);
  // Without a PnP fix: start the filter at the last estimate (or the prior) with a broad
  // covariance and match the frame's blobs to the lamps it predicts. False when too few match.
  bool acquire_from_guess(const CameraModel& camera);
  // Matches the blobs in matcher_ to the lamps the filter predicts; fills accepted_*,
  // result_.matched and result_.rejected. False when the match is ambiguous (refused).
  bool match_lamps();
  // Whether the estimate after this image's update is one the camera can have reached since the
  // last trusted estimate: then it becomes the trusted one; else result_ says it was refused.
  bool admit();
  void refuse(Refusal why);
  // The prediction of lamp i through the filter, dome included; false when it cannot be seen.
  bool predict_lamp(int i, const CameraModel& camera, PoseEkf::Prediction& out) const;
  double reprojection_rms(const CameraModel& camera) const;

  PlateMarkers plate_;
  TrackerSettings s_;
  BlobDetector detector_;
  PoseEkf ekf_;
  TrackState state_ = TrackState::kLost;
  FrameResult result_;
  // The filter's frame x (base or dev) relative to dev and base at the current image.
  Eigen::Isometry3d x_T_dev_ = Eigen::Isometry3d::Identity(), x_T_base_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d base_T_dev_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d last_eye_T_base_ = Eigen::Isometry3d::Identity();
  bool have_last_ = false;
  std::int64_t last_stamp_ = 0;
  bool have_stamp_ = false;
  Eigen::Isometry3d trusted_eye_T_base_ = Eigen::Isometry3d::Identity();  // the last admitted estimate
  std::int64_t trusted_stamp_ = 0;
  bool have_trusted_ = false;
  LampMatcher matcher_;
  std::vector<Blob> blobs_;
  std::vector<PoseEkf::Prediction> accepted_;
  std::vector<Eigen::Vector2d> accepted_pixels_;
  std::vector<int> accepted_ids_;
};

}  // namespace wysiwyf::vision
