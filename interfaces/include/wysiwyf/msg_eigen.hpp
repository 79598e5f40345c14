#pragma once
// Between geometry messages and Eigen: poses as Isometry3d (parent_T_child), twists as vectors.
#include <Eigen/Geometry>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::msgs {

inline Eigen::Isometry3d to_isometry(const geometry_msgs::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.orientation().w(), p.orientation().x(), p.orientation().y(), p.orientation().z())
                   .normalized()
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.position().x(), p.position().y(), p.position().z());
  return T;
}

inline void to_msg(const Eigen::Vector3d& position, const Eigen::Quaterniond& q, geometry_msgs::Pose& p) {
  p.position().x(position.x());
  p.position().y(position.y());
  p.position().z(position.z());
  p.orientation().x(q.x());
  p.orientation().y(q.y());
  p.orientation().z(q.z());
  p.orientation().w(q.w());
}

inline void to_msg(const Eigen::Isometry3d& T, geometry_msgs::Pose& p) {
  to_msg(T.translation(), Eigen::Quaterniond(T.linear()), p);
}

inline void to_msg(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular, geometry_msgs::Twist& t) {
  t.linear().x(linear.x()), t.linear().y(linear.y()), t.linear().z(linear.z());
  t.angular().x(angular.x()), t.angular().y(angular.y()), t.angular().z(angular.z());
}

}  // namespace wysiwyf::msgs
