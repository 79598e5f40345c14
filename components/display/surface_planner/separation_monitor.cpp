#include "separation_monitor.hpp"

#include <algorithm>

namespace wysiwyf::display {

double SeparationMonitor::kappa(const PlatePath& path, const robot::JointRef& q, const Eigen::Vector3d& hand) {
  const double peak = std::max(path.peak_velocity().norm(), 1e-9);
  const double scale = std::max(path.velocity().norm() / peak, 0.1);
  Eigen::Matrix<double, 6, 1> x;
  x << path.peak_velocity() * scale, path.peak_angular_velocity() * scale;
  // Joint rates at that velocity (damped least squares: near a singularity they stay finite).
  const robot::ArmJacobian J = model_.jacobian(q);
  const Eigen::Matrix<double, 6, 6> JJt = J * J.transpose() + 1e-4 * Eigen::Matrix<double, 6, 6>::Identity();
  const robot::JointVector qd = J.transpose() * JJt.ldlt().solve(x);
  double kappa = std::numeric_limits<double>::infinity();
  separation_ = std::numeric_limits<double>::infinity();
  for (const auto& p : clearance_.evaluate(q, qd, hand)) {
    const double s = std::max(0.0, p.distance - finger_radius_);
    if (s < separation_) separation_ = s, nearest_part_ = p.name;
    // (below a tenth of the peak the real approach is slower than judged: kappa stays safe)
    if (p.approach_speed > 1e-6) kappa = std::min(kappa, ssm_.allowed_speed(s) / p.approach_speed);
  }
  allowed_ = ssm_.allowed_speed(separation_);
  return kappa;
}

void SeparationMonitor::measure(const robot::JointRef& q, const Eigen::Vector3d& hand) {
  separation_ = std::numeric_limits<double>::infinity();
  for (const auto& p : clearance_.evaluate(q, still_, hand)) {
    const double s = std::max(0.0, p.distance - finger_radius_);
    if (s < separation_) separation_ = s, nearest_part_ = p.name;
  }
  allowed_ = ssm_.allowed_speed(separation_);
}

double SeparationMonitor::kappa_without_hand(const PlatePath& path) const {
  const double peak = path.peak_velocity().norm();
  return peak > 1e-9 ? without_hand_ / peak : 1.0;
}

double SeparationMonitor::braking_kappa(const PlatePath& path, double kappa, double dt) const {
  const double v_now = path.velocity().norm();
  const double v_next = v_now + path.speed_rate() * kappa * dt;
  if (v_next <= 1e-6) return 0.0;
  return std::max(0.0, (kappa * v_now - ssm_.braking_deceleration * dt) / v_next);
}

}  // namespace wysiwyf::display
