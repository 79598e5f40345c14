#pragma once
// Where the hand is and how it moves, from a tracker's noisy and late positions: a constant-
// velocity Kalman filter per axis (white acceleration), predicted to any time, so the tracker's
// latency is taken out and the hand's path can be extrapolated.
#include <cstdint>

#include <Eigen/Core>

namespace wysiwyf::display {

class HandFilter {
 public:
  // accel_density: the hand's acceleration, (m/s^2)^2 per Hz; people's reaches reach 10-20 m/s^2.
  explicit HandFilter(double accel_density = 20.0) : q_(accel_density) {}

  // A position measured at stamp_ns with variance `variance` (m^2, per axis).
  void update(std::int64_t stamp_ns, const Eigen::Vector3d& position, double variance);
  // Forget the hand (it was lost for too long).
  void reset() { valid_ = false; }

  bool valid() const { return valid_; }
  std::int64_t stamp_ns() const { return t_; }
  // Position and velocity predicted to now_ns.
  Eigen::Vector3d position(std::int64_t now_ns) const;
  Eigen::Vector3d velocity() const { return v_; }
  // The velocity with its noise shrunk away (|v|^2 / (|v|^2 + 9 var) of it): about nothing for a
  // hand at rest, most of it for a reaching one. What the hand's path is extrapolated with.
  Eigen::Vector3d significant_velocity() const {
    const double v2 = v_.squaredNorm();
    return v2 > 0 ? Eigen::Vector3d(v_ * (v2 / (v2 + 9 * 3 * P_(1, 1)))) : Eigen::Vector3d::Zero();
  }

 private:
  double q_;
  bool valid_ = false;
  std::int64_t t_ = 0;
  Eigen::Vector3d p_ = Eigen::Vector3d::Zero(), v_ = Eigen::Vector3d::Zero();
  Eigen::Matrix2d P_ = Eigen::Matrix2d::Identity();  // the same for every axis (same noise)
};

}  // namespace wysiwyf::display
