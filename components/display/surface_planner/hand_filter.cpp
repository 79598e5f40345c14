#include "hand_filter.hpp"

#include "wysiwyf/time.hpp"

namespace wysiwyf::display {

void HandFilter::update(std::int64_t stamp_ns, const Eigen::Vector3d& position, double variance) {
  if (!valid_) {
    valid_ = true;
    t_ = stamp_ns;
    p_ = position;
    v_.setZero();
    P_ << variance, 0, 0, 4.0;  // a hand at rest or moving at up to about 2 m/s
    return;
  }
  const double dt = std::max(0.0, static_cast<double>(elapsed_ns(stamp_ns, t_)) * 1e-9);
  // Predict: x = F x, P = F P F^T + Q (white acceleration of density q_).
  Eigen::Matrix2d F;
  F << 1, dt, 0, 1;
  Eigen::Matrix2d Q;
  Q << dt * dt * dt / 3, dt * dt / 2, dt * dt / 2, dt;
  P_ = F * P_ * F.transpose() + q_ * Q;
  p_ += v_ * dt;
  // Update with the position (H = [1 0]).
  const double s = P_(0, 0) + variance;
  const Eigen::Vector2d k(P_(0, 0) / s, P_(1, 0) / s);
  const Eigen::Vector3d innovation = position - p_;
  p_ += k[0] * innovation;
  v_ += k[1] * innovation;
  const Eigen::Matrix2d I_KH = (Eigen::Matrix2d() << 1 - k[0], 0, -k[1], 1).finished();
  P_ = I_KH * P_;
  t_ = stamp_ns;
}

Eigen::Vector3d HandFilter::position(std::int64_t now_ns) const {
  return p_ + v_ * std::max(0.0, static_cast<double>(now_ns - t_) * 1e-9);
}

}  // namespace wysiwyf::display
