#include "wysiwyf/msg_checks.hpp"

#include <cmath>
#include <string_view>

#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::msgs {

std::string pose_problem(const geometry_msgs::Pose& p) {
  if (!all_finite(p)) return "a non-finite pose";
  // to_isometry normalises: a quaternion a little off unit length is a rotation; one far off it
  // is not what any writer meant (and a zero one has no rotation at all).
  const double length = to_eigen(p.orientation()).norm();
  if (std::abs(length - 1.0) > 0.01)
    return "an orientation quaternion of length " + std::to_string(length) + " (expected 1)";
  return {};
}

std::string frame_problem(const std_msgs::Header& h, const char* expected) {
  if (std::string_view(h.frame_id().c_str()) == expected) return {};
  return "in frame '" + std::string(h.frame_id().c_str()) + "'; expected " + expected;
}

}  // namespace wysiwyf::msgs

namespace wysiwyf::msg {

std::string problem(const PoseStamped& m) { return msgs::pose_problem(m.pose()); }

std::string problem(const WrenchStamped& m) {
  return msgs::all_finite(m.wrench()) ? std::string() : "a non-finite force or torque";
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
  return {};
}

std::string problem(const HandPosition& m) {
  if (m.status() == TRACKING_LOST) return {};
  return msgs::to_eigen(m.position()).allFinite() ? std::string() : "a non-finite position";
}

std::string problem(const CartesianSetpoint& m) {
  if (std::string why = msgs::pose_problem(m.pose()); !why.empty()) return why;
  const bool twist = msgs::to_eigen(m.twist().linear()).allFinite() && msgs::to_eigen(m.twist().angular()).allFinite();
  return twist ? std::string() : "a non-finite twist";
}

std::string problem(const ObjectState& m) {
  if (std::string why = msgs::pose_problem(m.pose()); !why.empty()) return why;
  const bool twist = msgs::to_eigen(m.twist().linear()).allFinite() && msgs::to_eigen(m.twist().angular()).allFinite();
  return twist ? std::string() : "a non-finite twist";
}

std::string problem(const Attachment& m) {
  if (!m.attached()) return {};
  std::string why = msgs::pose_problem(m.obj_T_dev());
  return why.empty() ? why : why + " (obj_T_dev)";
}

}  // namespace wysiwyf::msg
