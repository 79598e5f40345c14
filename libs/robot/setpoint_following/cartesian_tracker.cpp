#include "setpoint_following/cartesian_tracker.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::robot {
namespace {

// Rotation vector of a unit quaternion (shortest way).
Eigen::Vector3d log_rotation(Eigen::Quaterniond q) {
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec();
  return 2.0 * std::atan2(s, q.w()) / s * q.vec();
}

Eigen::Quaterniond exp_rotation(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

}  // namespace

void CartesianTracker::reset(const Eigen::Isometry3d& pose, std::int64_t now_ns) {
  p_ = sp_p_ = pose.translation();
  r_ = sp_r_ = Eigen::Quaterniond(pose.linear());
  v_ = w_ = sp_v_ = sp_w_ = sp_a_ = sp_alpha_ = Eigen::Vector3d::Zero();
  sp_ns_ = now_ns;
  have_setpoint_ = false;
}

void CartesianTracker::set_setpoint(const Eigen::Isometry3d& pose, const Eigen::Vector3d& linear,
                                    const Eigen::Vector3d& angular, std::int64_t now_ns, double horizon) {
  const double since = static_cast<double>(now_ns - sp_ns_) * 1e-9;
  if (have_setpoint_ && since > 0.0 && since <= horizon) {
    sp_a_ = (linear - sp_v_) / since;
    sp_alpha_ = (angular - sp_w_) / since;
    if (sp_a_.norm() > kMaxLinearAccel) sp_a_ *= kMaxLinearAccel / sp_a_.norm();
    if (sp_alpha_.norm() > kMaxAngularAccel) sp_alpha_ *= kMaxAngularAccel / sp_alpha_.norm();
  } else if (!have_setpoint_ || since > horizon) {
    sp_a_ = sp_alpha_ = Eigen::Vector3d::Zero();
  }  // (several setpoints in one tick: keep the estimate)
  sp_p_ = pose.translation();
  sp_r_ = Eigen::Quaterniond(pose.linear());
  sp_v_ = linear;
  sp_w_ = angular;
  sp_ns_ = now_ns;
  have_setpoint_ = true;
}

Eigen::Isometry3d CartesianTracker::advance(std::int64_t now_ns, double dt, double omega, double horizon) {
  const double since = static_cast<double>(now_ns - sp_ns_) * 1e-9;
  const bool extrapolate = since <= horizon;
  const double tau = std::min(since, horizon);
  const Eigen::Vector3d a_target = extrapolate ? sp_a_ : Eigen::Vector3d::Zero();
  const Eigen::Vector3d alpha_target = extrapolate ? sp_alpha_ : Eigen::Vector3d::Zero();
  const Eigen::Vector3d p_target = sp_p_ + sp_v_ * tau + 0.5 * tau * tau * sp_a_;
  const Eigen::Vector3d v_target = extrapolate ? Eigen::Vector3d(sp_v_ + sp_a_ * tau) : Eigen::Vector3d::Zero();
  const Eigen::Quaterniond r_target = exp_rotation(sp_w_ * tau + 0.5 * tau * tau * sp_alpha_) * sp_r_;
  const Eigen::Vector3d w_target = extrapolate ? Eigen::Vector3d(sp_w_ + sp_alpha_ * tau) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d a = a_target + omega * omega * (p_target - p_) + 2.0 * omega * (v_target - v_);
  v_ += a * dt;
  p_ += v_ * dt;
  const Eigen::Vector3d alpha =
      alpha_target + omega * omega * log_rotation(r_target * r_.conjugate()) + 2.0 * omega * (w_target - w_);
  w_ += alpha * dt;
  r_ = (exp_rotation(w_ * dt) * r_).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = r_.toRotationMatrix();
  T.translation() = p_;
  return T;
}

}  // namespace wysiwyf::robot
