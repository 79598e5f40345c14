#include "setpoint_preview.hpp"

#include <cmath>

namespace wysiwyf::haptics {
namespace {

// Rotation vector of R (its angle times its axis).
Eigen::Vector3d log_rotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d exp_rotation(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

}  // namespace

SetpointPreview::SetpointPreview(std::size_t half_samples, double dt)
    : half_(half_samples), dt_(dt), past_(half_samples + 1), future_(half_samples) {
  restart(Eigen::Isometry3d::Identity());
}

void SetpointPreview::restart(const Eigen::Isometry3d& pose) {
  for (Eigen::Isometry3d& p : past_) p = pose;
  for (Eigen::Isometry3d& p : future_) p = pose;
  newest_ = 0;
}

void SetpointPreview::record(const Eigen::Isometry3d& pose) {
  newest_ = (newest_ + 1) % past_.size();
  past_[newest_] = pose;
}

const Eigen::Isometry3d& SetpointPreview::sample(long k) const {
  if (k > 0) return future_[static_cast<std::size_t>(k - 1)];
  const long n = static_cast<long>(past_.size());
  return past_[static_cast<std::size_t>(((static_cast<long>(newest_) + k) % n + n) % n)];
}

PreviewedSetpoint SetpointPreview::setpoint() const {
  PreviewedSetpoint out;
  const Eigen::Isometry3d& now = sample(0);
  if (half_ == 0) {
    out.pose = now;
    return out;
  }
  // The trapezoidal rule over the 2 half + 1 samples; rotations as rotation vectors from now's
  // (within a window of milliseconds they are small, where the average of rotation vectors is
  // the rotations' mean to second order).
  const long h = static_cast<long>(half_);
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), r = Eigen::Vector3d::Zero();
  const Eigen::Matrix3d now_inv = now.linear().transpose();
  for (long k = -h; k <= h; ++k) {
    const double w = (k == -h || k == h) ? 0.5 : 1.0;
    const Eigen::Isometry3d& s = sample(k);
    p += w * s.translation();
    r += w * log_rotation(s.linear() * now_inv);
  }
  const double n = static_cast<double>(2 * h);
  out.pose.translation() = p / n;
  out.pose.linear() = exp_rotation(r / n) * now.linear();
  const Eigen::Isometry3d& first = sample(-h);
  const Eigen::Isometry3d& last = sample(h);
  const double window = n * dt_;
  out.linear = (last.translation() - first.translation()) / window;
  out.angular = log_rotation(last.linear() * first.linear().transpose()) / window;
  return out;
}

}  // namespace wysiwyf::haptics
