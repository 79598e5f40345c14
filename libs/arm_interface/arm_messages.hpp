#pragma once
// The arm's measurements as messages, the same from puma_sim and puma_driver: joint_state
// (angles, velocities, motor torques) and device_pose (base_T_<tip> by FK), both in frame "base".
#include <cstdint>
#include <string>

#include <Eigen/Geometry>

#include "puma_model/types.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot {

void fill_joint_state(msg::JointState& m, std::int64_t stamp_ns, std::uint64_t seq, const Vector6d& q,
                      const Vector6d& qd, const Vector6d& effort);
void fill_device_pose(msg::PoseStamped& m, std::int64_t stamp_ns, std::uint64_t seq, const std::string& tip_frame,
                      const Eigen::Isometry3d& base_T_tip);

}  // namespace wysiwyf::robot
