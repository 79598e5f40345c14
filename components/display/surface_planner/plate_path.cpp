#include "plate_path.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::display {

namespace {

// A minimum-jerk move over a distance d peaks at 1.875 d / T in speed and 5.77 d / T^2 in
// acceleration: the shortest T within both limits.
double duration(double d, double v_max, double a_max) {
  return d <= 0 ? 0.0 : std::max(1.875 * d / v_max, std::sqrt(5.7735 * d / a_max));
}

}  // namespace

void PlatePath::plan(const Eigen::Isometry3d& from, const std::vector<Eigen::Vector3d>& via,
                     const Eigen::Isometry3d& to) {
  std::vector<Eigen::Vector3d> points{from.translation()};
  points.insert(points.end(), via.begin(), via.end());
  points.push_back(to.translation());
  // The turn is spread over all segments but the last (by length; all of it on the first when
  // they have none), so the plate comes out square to the face.
  const Eigen::Quaterniond q_from = Eigen::Quaterniond(from.linear()).normalized();
  Eigen::Quaterniond q_to = Eigen::Quaterniond(to.linear()).normalized();
  if (q_from.dot(q_to) < 0) q_to.coeffs() *= -1;
  const std::size_t turning = std::max<std::size_t>(1, points.size() - 2);
  double turn_length = 0;
  for (std::size_t i = 0; i < turning; ++i) turn_length += (points[i + 1] - points[i]).norm();
  segments_.clear();
  double along = 0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    Segment seg;
    seg.p0 = points[i], seg.p1 = points[i + 1];
    const double length = (seg.p1 - seg.p0).norm();
    auto turned = [&](double at) {
      return i >= turning ? 1.0 : turn_length > 0 ? at / turn_length : (i == 0 ? 1.0 : 0.0);
    };
    const double f0 = i == 0 ? 0.0 : std::min(1.0, turned(along));
    along += length;
    const double f1 = std::min(1.0, i + 1 >= turning ? 1.0 : turned(along));
    seg.q0 = q_from.slerp(f0, q_to);
    seg.q1 = q_from.slerp(f1, q_to);
    const double angle = seg.q0.angularDistance(seg.q1);
    seg.duration = std::max(duration(length, limits_.speed, limits_.acceleration),
                            duration(angle, limits_.angular_speed, limits_.angular_acceleration));
    if (seg.duration > 0) segments_.push_back(seg);
  }
  to_ = to;
  index_ = 0;
  tau_ = 0;
}

double PlatePath::s() const { return tau_ * tau_ * tau_ * (10 - 15 * tau_ + 6 * tau_ * tau_); }
double PlatePath::ds() const { return 30 * tau_ * tau_ * (1 - 2 * tau_ + tau_ * tau_) / segments_[index_].duration; }

double PlatePath::dds() const {
  const double T = segments_[index_].duration;
  return 60 * tau_ * (1 - 3 * tau_ + 2 * tau_ * tau_) / (T * T);
}

void PlatePath::advance(double dt, double kappa) {
  if (done()) return;
  tau_ += kappa * dt / segments_[index_].duration;
  if (tau_ >= 1.0) {
    ++index_;
    tau_ = 0;
  }
}

Eigen::Isometry3d PlatePath::pose() const {
  if (done()) return to_;
  const Segment& g = segments_[index_];
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = g.p0 + s() * (g.p1 - g.p0);
  T.linear() = g.q0.slerp(s(), g.q1).toRotationMatrix();
  return T;
}

Eigen::Vector3d PlatePath::velocity() const {
  if (done()) return Eigen::Vector3d::Zero();
  const Segment& g = segments_[index_];
  return (g.p1 - g.p0) * ds();
}

double PlatePath::speed_rate() const {
  if (done()) return 0.0;
  const Segment& g = segments_[index_];
  return (g.p1 - g.p0).norm() * dds();
}

Eigen::Vector3d PlatePath::angular_velocity() const {
  if (done()) return Eigen::Vector3d::Zero();
  const Segment& g = segments_[index_];
  const Eigen::AngleAxisd turn(g.q1 * g.q0.inverse());
  return turn.axis() * (turn.angle() * ds());
}

Eigen::Vector3d PlatePath::peak_velocity() const {
  if (done()) return Eigen::Vector3d::Zero();
  const Segment& g = segments_[index_];
  return (g.p1 - g.p0) * (1.875 / g.duration);
}

Eigen::Vector3d PlatePath::peak_angular_velocity() const {
  if (done()) return Eigen::Vector3d::Zero();
  const Segment& g = segments_[index_];
  const Eigen::AngleAxisd turn(g.q1 * g.q0.inverse());
  return turn.axis() * (turn.angle() * 1.875 / g.duration);
}

double PlatePath::remaining_time() const {
  if (done()) return 0.0;
  double t = (1 - tau_) * segments_[index_].duration;
  for (std::size_t i = index_ + 1; i < segments_.size(); ++i) t += segments_[i].duration;
  return t;
}

}  // namespace wysiwyf::display
