#include "wysiwyf/msg_checks.hpp"

#include <cmath>
#include <initializer_list>
#include <string_view>

#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::msgs {

namespace {

// Finite and within kMaxMagnitude, every element.
template <class Values>
bool within_magnitude(const Values& v) {
  for (double x : v)
    if (!(std::abs(x) <= kMaxMagnitude)) return false;  // (false for a NaN too)
  return true;
}
bool within_magnitude(const Eigen::Vector3d& v) {
  return within_magnitude(std::initializer_list<double>{v.x(), v.y(), v.z()});
}

const std::string kBeyond = " (expected finite, within 1e4)";

}  // namespace

std::string pose_problem(const geometry_msgs::Pose& p) {
  if (!all_finite(p)) return "a non-finite pose";
  if (!within_magnitude(to_eigen(p.position()))) return "a position beyond 1e4 m" + kBeyond;
  // to_isometry normalises: a quaternion a little off unit length is a rotation; one far off it
  // is not what any writer meant (and a zero one has no rotation at all).
  const double length = to_eigen(p.orientation()).norm();
  if (std::abs(length - 1.0) > 0.01)
    return "an orientation quaternion of length " + std::to_string(length) + " (expected 1)";
  return {};
}

std::string twist_problem(const geometry_msgs::Twist& t) {
  if (!to_eigen(t.linear()).allFinite() || !to_eigen(t.angular()).allFinite()) return "a non-finite twist";
  return within_magnitude(to_eigen(t.linear())) && within_magnitude(to_eigen(t.angular()))
             ? std::string()
             : "a twist beyond 1e4 m/s or rad/s" + kBeyond;
}

std::string frame_problem(const std_msgs::Header& h, const char* expected) {
  if (std::string_view(h.frame_id().c_str()) == expected) return {};
  return "in frame '" + std::string(h.frame_id().c_str()) + "'; expected " + expected;
}

}  // namespace wysiwyf::msgs

namespace wysiwyf::msg {

std::string problem(const PoseStamped& m) { return msgs::pose_problem(m.pose()); }

std::string problem(const WrenchStamped& m) {
  if (!msgs::all_finite(m.wrench())) return "a non-finite force or torque";
  const bool within = msgs::within_magnitude(msgs::to_eigen(m.wrench().force())) &&
                      msgs::within_magnitude(msgs::to_eigen(m.wrench().torque()));
  return within ? std::string() : "a force or torque beyond 1e4" + msgs::kBeyond;
}

std::string problem(const JointState& m) {
  const std::size_t n = m.position().size();
  if (n == 0) return "no joint positions";
  if (!m.velocity().empty() && m.velocity().size() != n)
    return std::to_string(m.velocity().size()) + " velocities for " + std::to_string(n) + " joints";
  if (!m.effort().empty() && m.effort().size() != n)
    return std::to_string(m.effort().size()) + " efforts for " + std::to_string(n) + " joints";
  for (double q : m.position())
    if (!std::isfinite(q)) return "a non-finite joint position";
  // (an unknown velocity or effort may be NaN: not a magnitude)
  const auto known_within = [](const auto& values) {
    for (double x : values)
      if (!std::isnan(x) && !(std::abs(x) <= msgs::kMaxMagnitude)) return false;
    return true;
  };
  if (!msgs::within_magnitude(m.position()) || !known_within(m.velocity()) || !known_within(m.effort()))
    return "a joint position, velocity or effort beyond 1e4" + msgs::kBeyond;
  return {};
}

std::string problem(const HandPosition& m) {
  if (m.status() == TRACKING_LOST) return {};
  if (!msgs::to_eigen(m.position()).allFinite()) return "a non-finite position";
  return msgs::within_magnitude(msgs::to_eigen(m.position())) ? std::string()
                                                              : "a position beyond 1e4 m" + msgs::kBeyond;
}

std::string problem(const CartesianSetpoint& m) {
  if (std::string why = msgs::pose_problem(m.pose()); !why.empty()) return why;
  return msgs::twist_problem(m.twist());
}

std::string problem(const ObjectState& m) {
  if (std::string why = msgs::pose_problem(m.pose()); !why.empty()) return why;
  return msgs::twist_problem(m.twist());
}

std::string problem(const Attachment& m) {
  if (!m.attached()) return {};
  std::string why = msgs::pose_problem(m.obj_T_dev());
  return why.empty() ? why : why + " (obj_T_dev)";
}

}  // namespace wysiwyf::msg
