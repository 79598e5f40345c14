#pragma once
// An extended Kalman filter on one pose eye_T_x (x is the robot base, or the device plate in the
// paper's first variant) with a constant-velocity model, measured through the pixels of points
// known in frame x. Error state (12): [dt, dtheta, dv, dw] with t = t^ + dt, R = exp(dtheta) R^
// (rotation errors in eye coordinates), v and w the translational and angular velocity in eye
// coordinates. Process noise: white acceleration of the given spectral densities, driving
// velocities that either persist (constant velocity) or decay with a correlation time (a first
// order Gauss-Markov velocity: a camera that moves in short motions and is otherwise still).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

#include "camera_model.hpp"

namespace wysiwyf::vision {

// Process noise (white acceleration) and measurement noise of PoseEkf.
struct EkfNoise {
  double accel = 3e-4;          // m/s^2 per sqrt(Hz): translational acceleration
  double angular_accel = 3e-4;  // rad/s^2 per sqrt(Hz)
  double pixel = 0.1;           // px: a centroid's measurement noise (sigma)
  // s: how long a velocity lasts (its correlation time). A camera on a stand or a head moves in
  // short motions and is still in between: a velocity that persists for seconds would carry the
  // pose along whatever direction the lamps pin least (along the line of sight). 0: constant
  // velocity, for a state that moves at sustained speeds.
  double velocity_time = 0.2;
};

class PoseEkf {
 public:
  static constexpr int kStates = 12;
  using StateMatrix = Eigen::Matrix<double, kStates, kStates>;
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  using Jacobian = Eigen::Matrix<double, 2, kStates>;

  using Noise = EkfNoise;

  // One predicted marker: its pixel, the Jacobian of that pixel, and the innovation covariance.
  struct Prediction {
    Eigen::Vector2d pixel;
    Jacobian H;
    Eigen::Matrix2d S;
    double depth = 0;  // of the point in the eye frame, m
  };

  explicit PoseEkf(Noise noise = {}) : noise_(noise) {}

  // Starts at eye_T_x at rest, with the given pose covariance (over dt, dtheta) and velocity
  // standard deviations.
  void reset(const Eigen::Isometry3d& eye_T_x, const Matrix6d& pose_cov, double velocity_sigma, double angular_sigma);
  void predict(double dt_s);
  // The pose made more uncertain by `added` (over dt, dtheta), the velocities and what is known
  // of them kept: the pose has been unseen for a while, the camera's dynamics are the same.
  void widen_pose(const Matrix6d& added) { P_.topLeftCorner<6, 6>() += added; }
  // The pixel of point x_p (in frame x) displaced by eye_offset (eye frame, not estimated: the
  // lamp's dome, see plate_markers.hpp). False when the point is behind the camera.
  bool predict_pixel(const Eigen::Vector3d& x_p, const Eigen::Vector3d& eye_offset, const CameraModel& camera,
                     Prediction& out) const;
  // Squared Mahalanobis distance of a measured (ideal) pixel from a prediction.
  static double mahalanobis2(const Prediction& p, const Eigen::Vector2d& pixel) {
    const Eigen::Vector2d y = pixel - p.pixel;
    return y.dot(p.S.ldlt().solve(y));
  }
  // Squared Mahalanobis distance of several measured (ideal) pixels from their predictions taken
  // together: their errors are correlated through the pose's, so a set of pixels that each lie
  // near their own prediction may still be far from any one pose. At most 8 pixels.
  double joint_mahalanobis2(const Prediction* const predictions[], const Eigen::Vector2d pixels[], int count) const;
  // One update with all accepted measurements: pixels[i] is the measurement of predictions[i].
  void update(const std::vector<Prediction>& predictions, const std::vector<Eigen::Vector2d>& pixels);

  const Eigen::Isometry3d& pose() const { return eye_T_x_; }
  const Eigen::Vector3d& velocity() const { return v_; }
  const Eigen::Vector3d& angular_velocity() const { return w_; }
  // Covariance of (dt, dtheta), eye coordinates.
  Matrix6d pose_covariance() const { return P_.topLeftCorner<6, 6>(); }
  const StateMatrix& covariance() const { return P_; }
  const Noise& noise() const { return noise_; }

 private:
  Noise noise_;
  Eigen::Isometry3d eye_T_x_ = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_ = Eigen::Vector3d::Zero(), w_ = Eigen::Vector3d::Zero();
  StateMatrix P_ = StateMatrix::Identity();
};

}  // namespace wysiwyf::vision
