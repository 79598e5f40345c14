#include "arm_interface/arm_messages.hpp"

#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot {

void fill_joint_state(msg::JointState& m, std::int64_t stamp_ns, std::uint64_t seq, const Vector6d& q,
                      const Vector6d& qd, const Vector6d& effort) {
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.header().frame_id("base");
  for (int j = 0; j < kDof; ++j) {
    const auto k = static_cast<std::size_t>(j);
    m.position()[k] = q[j];
    m.velocity()[k] = qd[j];
    m.effort()[k] = effort[j];
  }
}

void fill_device_pose(msg::PoseStamped& m, std::int64_t stamp_ns, std::uint64_t seq, const std::string& tip_frame,
                      const Eigen::Isometry3d& base_T_tip) {
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.header().frame_id("base");
  m.child_frame_id(tip_frame);
  msgs::to_msg(base_T_tip, m.pose());
}

}  // namespace wysiwyf::robot
