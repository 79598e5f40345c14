#pragma once
// The plate's way from where it is to the pose that displays a feature: straight segments through
// via points, each a minimum-jerk motion that starts and ends at rest (no corner is cut, nothing
// overshoots when the arm lags), the orientation turning over all but the last segment so the
// plate arrives square to the face along its normal. Each segment's duration comes from the top
// linear and angular speeds and accelerations; the planner runs the path's clock at a rate kappa
// in [0, 1] that speed and separation monitoring may lower.
#include <vector>

#include <Eigen/Geometry>

namespace wysiwyf::display {

struct PathLimits {
  double speed = 0.6;                 // m/s
  double acceleration = 2.0;          // m/s^2
  double angular_speed = 1.5;         // rad/s
  double angular_acceleration = 6.0;  // rad/s^2
};

class PlatePath {
 public:
  explicit PlatePath(PathLimits limits = {}) : limits_(limits) {}

  void plan(const Eigen::Isometry3d& from, const std::vector<Eigen::Vector3d>& via, const Eigen::Isometry3d& to);
  void clear() { segments_.clear(), index_ = 0, tau_ = 0; }

  bool done() const { return index_ >= segments_.size(); }
  // Moves the path's clock on by dt seconds run at rate kappa (1: full speed).
  void advance(double dt, double kappa);

  Eigen::Isometry3d pose() const;
  const Eigen::Isometry3d& goal() const { return to_; }
  // The plate's linear and angular velocity now at kappa 1.
  Eigen::Vector3d velocity() const;
  Eigen::Vector3d angular_velocity() const;
  // How fast the plate's speed grows now at kappa 1, m/s^2 (negative: slowing); a segment is straight.
  double speed_rate() const;
  // The current segment's peak velocities at kappa 1 (its direction holds along the segment).
  Eigen::Vector3d peak_velocity() const;
  Eigen::Vector3d peak_angular_velocity() const;
  // Seconds to the end at full speed.
  double remaining_time() const;

 private:
  struct Segment {
    Eigen::Vector3d p0, p1;
    Eigen::Quaterniond q0, q1;
    double duration = 0;
  };
  double s() const;    // minimum-jerk progress of the current segment
  double ds() const;   // its derivative in time, at full speed
  double dds() const;  // its second derivative

  PathLimits limits_;
  std::vector<Segment> segments_;
  std::size_t index_ = 0;
  double tau_ = 0;  // 0..1 within the current segment
  Eigen::Isometry3d to_ = Eigen::Isometry3d::Identity();
};

}  // namespace wysiwyf::display
