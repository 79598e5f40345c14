#pragma once
// Between geometry messages and Eigen: poses as Isometry3d (parent_T_child), vectors, twists and
// wrenches. The one place these fields are copied one by one.
#include <Eigen/Geometry>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::msgs {

using Vector6d = Eigen::Matrix<double, 6, 1>;

inline Eigen::Vector3d to_eigen(const geometry_msgs::Vector3& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Vector3d to_eigen(const geometry_msgs::Point& p) { return {p.x(), p.y(), p.z()}; }
inline Eigen::Quaterniond to_eigen(const geometry_msgs::Quaternion& q) { return {q.w(), q.x(), q.y(), q.z()}; }

inline void to_msg(const Eigen::Vector3d& v, geometry_msgs::Vector3& out) { out.x(v.x()), out.y(v.y()), out.z(v.z()); }
inline void to_msg(const Eigen::Vector3d& v, geometry_msgs::Point& out) { out.x(v.x()), out.y(v.y()), out.z(v.z()); }

inline Eigen::Isometry3d to_isometry(const geometry_msgs::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = to_eigen(p.orientation()).normalized().toRotationMatrix();
  T.translation() = to_eigen(p.position());
  return T;
}

inline void to_msg(const Eigen::Vector3d& position, const Eigen::Quaterniond& q, geometry_msgs::Pose& p) {
  to_msg(position, p.position());
  p.orientation().x(q.x());
  p.orientation().y(q.y());
  p.orientation().z(q.z());
  p.orientation().w(q.w());
}

inline void to_msg(const Eigen::Isometry3d& T, geometry_msgs::Pose& p) {
  to_msg(T.translation(), Eigen::Quaterniond(T.linear()), p);
}

inline void to_msg(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular, geometry_msgs::Twist& t) {
  to_msg(linear, t.linear());
  to_msg(angular, t.angular());
}

inline void to_msg(const Eigen::Vector3d& force, const Eigen::Vector3d& torque, geometry_msgs::Wrench& w) {
  to_msg(force, w.force());
  to_msg(torque, w.torque());
}

// A wrench as (fx fy fz tx ty tz), and back.
inline Vector6d to_vector6(const geometry_msgs::Wrench& w) {
  Vector6d v;
  v << to_eigen(w.force()), to_eigen(w.torque());
  return v;
}
inline void to_msg(const Vector6d& v, geometry_msgs::Wrench& w) { to_msg(v.head<3>(), v.tail<3>(), w); }

// `pose` (its header, child frame and pose) with its 6x6 covariance (row-major; the order of the
// PoseWithCovariance's comment) as a PoseWithCovariance.
inline void to_msg(const msg::PoseStamped& pose, const Eigen::Matrix<double, 6, 6>& covariance,
                   msg::PoseWithCovariance& out) {
  out.header() = pose.header();
  out.child_frame_id(pose.child_frame_id());
  out.pose() = pose.pose();
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) out.covariance()[static_cast<std::size_t>(6 * r + c)] = covariance(r, c);
}

// A six-joint arm's positions as one vector.

inline bool all_finite(const geometry_msgs::Wrench& w) { return to_vector6(w).allFinite(); }
inline bool all_finite(const geometry_msgs::Pose& p) {
  return to_eigen(p.position()).allFinite() && to_eigen(p.orientation()).coeffs().allFinite();
}

}  // namespace wysiwyf::msgs
