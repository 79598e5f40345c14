#include "setpoint_following/setpoint_follower.hpp"

#include <utility>

#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot {

SetpointFollower::SetpointFollower(const PumaModel& model, std::string tip_name, SafetyGate& gate, double tracker_hz,
                                   double dt)
    : model_(model), tip_name_(std::move(tip_name)), gate_(gate), omega_(6.283185307179586 * tracker_hz), dt_(dt) {}

void SetpointFollower::take(const msg::CartesianSetpoint& m, std::int64_t now_ns) {
  const std::string frame = m.header().frame_id().c_str(), child = m.child_frame_id().c_str();
  if ((!frame.empty() && frame != "base" && frame != "base_link") || (!child.empty() && child != tip_name_)) {
    gate_.fault("setpoint rejected: it places '" + child + "' in '" + frame + "'; this arm follows base_T_" +
                tip_name_);
    return;
  }
  // The quaternion as sent, not normalised: the gate refuses unnormalised ones.
  SetpointInput in;
  in.position = msgs::to_eigen(m.pose().position());
  in.quaternion_xyzw = msgs::to_eigen(m.pose().orientation()).coeffs();
  in.linear_velocity = msgs::to_eigen(m.twist().linear());
  in.angular_velocity = msgs::to_eigen(m.twist().angular());
  const bool was_following = gate_.following();
  const Eigen::Isometry3d reference_pose = model_.fk(gate_.reference().q);
  Eigen::Isometry3d pose;
  if (!gate_.accept_setpoint(now_ns, in, reference_pose, pose)) return;
  source_ = m.source().c_str();
  if (!was_following) tracker_.reset(reference_pose, now_ns);  // start (again) from where the arm is
  tracker_.set_setpoint(pose, in.linear_velocity, in.angular_velocity, now_ns, gate_.config().setpoint_timeout);
}

void SetpointFollower::update(std::int64_t now_ns) {
  if (gate_.following()) {
    const Eigen::Isometry3d pose = tracker_.advance(now_ns, dt_, omega_, gate_.config().setpoint_timeout);
    const Vector6d& seed = have_target_ ? q_target_ : gate_.reference().q;
    const IkResult ik = model_.ik_nearest(pose, seed);
    const Vector6d qd_target = have_target_ && ik.ok() ? Vector6d((ik.q - q_target_) / dt_) : Vector6d::Zero();
    gate_.set_joint_target(ik, qd_target);
    if (gate_.following()) {
      q_target_ = ik.q;
      have_target_ = true;
    }
  }
  if (!gate_.following()) have_target_ = false;
}

}  // namespace wysiwyf::robot
