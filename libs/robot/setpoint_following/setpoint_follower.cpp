#include "setpoint_following/setpoint_follower.hpp"

#include <cstdio>
#include <utility>

#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot {

SetpointFollower::SetpointFollower(const ArmModel& model, std::string tip_name, SafetyGate& gate, double tracker_hz,
                                   double dt)
    : model_(model),
      tip_name_(std::move(tip_name)),
      gate_(gate),
      omega_(6.283185307179586 * tracker_hz),
      dt_(dt),
      q_target_(JointVector::Zero(model.dof())) {}

SetpointFollower::Taken SetpointFollower::take(const msg::CartesianSetpoint& m, std::int64_t now_ns,
                                               std::string_view writer) {
  // The stamp first: a stale, replayed or future setpoint is not followed, and says nothing of
  // the stream's health (it does not feed the watchdog). (A zero stamp is stale, but at t = 0 of
  // a sim clock, where it is the time.)
  const std::int64_t stamp = m.header().stamp_ns();
  const SafetyConfig& c = gate_.config();
  // In doubles: a stamp from outside may be anything, and INT64_MIN would overflow the int64
  // difference into "far in the future".
  const double age = (static_cast<double>(now_ns) - static_cast<double>(stamp)) * 1e-9;
  const auto refuse = [&](const char* fmt, double a, double b) {
    char buf[200];
    std::snprintf(buf, sizeof buf, fmt, a, b);
    refusal_ = buf;
    return Taken::kRefused;
  };
  if (age > c.max_setpoint_age)
    return refuse("stale: stamped %.1f ms ago (max_setpoint_age %.1f ms)", age * 1e3, c.max_setpoint_age * 1e3);
  if (-age > c.max_setpoint_lead)
    return refuse("from the future: stamped %.1f ms ahead (max_setpoint_lead %.1f ms)", -age * 1e3,
                  c.max_setpoint_lead * 1e3);
  if (gate_.following() && stamp < last_stamp_ns_)
    return refuse("out of order: stamped %.3f ms before the last followed setpoint",
                  static_cast<double>(last_stamp_ns_ - stamp) * 1e-6, 0.0);  // (an unused argument is allowed)
  const std::string frame = m.header().frame_id().c_str(), child = m.child_frame_id().c_str();
  if ((!frame.empty() && frame != "base" && frame != "base_link") || (!child.empty() && child != tip_name_)) {
    gate_.fault("setpoint rejected: it places '" + child + "' in '" + frame + "'; this arm follows base_T_" + tip_name_,
                FaultCause::kInput);
    return Taken::kFaulted;
  }
  // The quaternion as sent, not normalised: the gate refuses unnormalised ones.
  SetpointInput in;
  in.position = msgs::to_eigen(m.pose().position());
  in.quaternion_xyzw = msgs::to_eigen(m.pose().orientation()).coeffs();
  in.linear_velocity = msgs::to_eigen(m.twist().linear());
  in.angular_velocity = msgs::to_eigen(m.twist().angular());
  in.source = m.source().c_str();
  in.stamp_ns = stamp;
  in.writer = writer;
  const bool was_following = gate_.following();
  const Eigen::Isometry3d reference_pose = model_.fk(gate_.reference().q);
  Eigen::Isometry3d pose;
  if (!gate_.accept_setpoint(now_ns, in, reference_pose, pose)) return Taken::kFaulted;
  source_ = m.source().c_str();
  last_stamp_ns_ = stamp;
  if (!was_following) tracker_.reset(reference_pose, now_ns);  // start (again) from where the arm is
  tracker_.set_setpoint(pose, in.linear_velocity, in.angular_velocity, now_ns, loss_timeout());
  return Taken::kFollowed;
}

double SetpointFollower::loss_timeout() const { return static_cast<double>(gate_.setpoint_loss_timeout_ns()) * 1e-9; }

void SetpointFollower::update(std::int64_t now_ns) {
  if (gate_.following()) {
    // Extrapolated for one period of the stream, no longer: an overdue setpoint is not
    // guessed at, the tracker decelerates onto the last one (none before the period is known).
    const double horizon = static_cast<double>(gate_.setpoint_period_ns()) * 1e-9;
    const Eigen::Isometry3d pose = tracker_.advance(now_ns, dt_, omega_, horizon);
    const JointVector& seed = have_target_ ? q_target_ : gate_.reference().q;
    const ArmIkResult ik = model_.ik_nearest(pose, seed);
    const JointVector qd_target =
        have_target_ && ik.ok() ? JointVector((ik.q - q_target_) / dt_) : JointVector::Zero(model_.dof());
    gate_.set_joint_target(ik, qd_target);
    if (gate_.following()) {
      q_target_ = ik.q;
      have_target_ = true;
    }
  }
  if (!gate_.following()) have_target_ = false;
}

}  // namespace wysiwyf::robot
