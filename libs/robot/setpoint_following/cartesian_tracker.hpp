#pragma once
// The RCCL-style Cartesian trajectory generator: a critically damped second-order tracker
// (natural frequency omega) on the latest setpoint, extrapolated by its twist and by the
// acceleration that the last two twists imply (a second-order hold: a smooth path streamed at
// 20 ms then gives the tracker almost nothing to correct at each new setpoint). The pose it puts
// out has a continuous velocity whatever the setpoint period (1 to 20 ms).
#include <cstdint>

#include <Eigen/Geometry>

namespace wysiwyf::robot {

class CartesianTracker {
 public:
  static constexpr double kMaxLinearAccel = 20.0;   // m/s^2, cap on the estimated acceleration
  static constexpr double kMaxAngularAccel = 60.0;  // rad/s^2

  // Starts at rest at `pose`, with no setpoint.
  void reset(const Eigen::Isometry3d& pose, std::int64_t now_ns);
  // A new setpoint (pose and twist in base coordinates) arriving at now_ns; an acceleration is
  // estimated from the previous twist if that one came within `horizon` seconds.
  void set_setpoint(const Eigen::Isometry3d& pose, const Eigen::Vector3d& linear, const Eigen::Vector3d& angular,
                    std::int64_t now_ns, double horizon);
  // One step of dt to now_ns; extrapolation stops `horizon` seconds after the last setpoint.
  Eigen::Isometry3d advance(std::int64_t now_ns, double dt, double omega, double horizon);

 private:
  Eigen::Vector3d p_ = Eigen::Vector3d::Zero(), v_ = Eigen::Vector3d::Zero(), w_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond r_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d sp_p_ = Eigen::Vector3d::Zero(), sp_v_ = Eigen::Vector3d::Zero(), sp_w_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d sp_a_ = Eigen::Vector3d::Zero(), sp_alpha_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond sp_r_ = Eigen::Quaterniond::Identity();
  std::int64_t sp_ns_ = 0;
  bool have_setpoint_ = false;
};

}  // namespace wysiwyf::robot
