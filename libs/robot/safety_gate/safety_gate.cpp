// SafetyGate: setpoint screening, watchdog, fault latch and the bounded-acceleration reference
// (see safety_gate.hpp for what it guarantees and why).
#include "safety_gate/safety_gate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace wysiwyf::robot {
namespace {

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

const char* to_string(SafetyState state) {
  switch (state) {
    case SafetyState::kOk: return "ok";
    case SafetyState::kHolding: return "holding";
    case SafetyState::kFault: return "fault";
  }
  return "unknown";
}

void SafetyConfig::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("safety gate: " + what); };
  const int n = dof();
  if (n < 1 || n > kMaxArmDof)
    fail("the joint limits hold " + std::to_string(n) + " joints, need 1.." + std::to_string(kMaxArmDof));
  const auto sized = [&](const JointVector& v, const char* what) {
    if (v.size() != n)
      fail(std::string(what) + " has " + std::to_string(v.size()) + " values, need one per joint (" +
           std::to_string(n) + ")");
  };
  sized(limits.upper, "the upper position limit");
  sized(limits.velocity, "the velocity limit");
  sized(max_acceleration, "acceleration_limits");
  for (int j = 0; j < n; ++j) {
    const std::string joint = "joint " + std::to_string(j + 1);
    if (!(limits.lower[j] < limits.upper[j])) fail(joint + ": lower limit must be below the upper limit");
    if (!(limits.velocity[j] > 0.0) || !std::isfinite(limits.velocity[j])) fail(joint + ": velocity limit must be > 0");
    if (!(max_acceleration[j] > 0.0) || !std::isfinite(max_acceleration[j]))
      fail(joint + ": acceleration limit must be > 0");
    if (!(2.0 * position_margin < limits.upper[j] - limits.lower[j]))
      fail(joint + ": position_margin leaves no room between the limits");
  }
  if (!(position_margin >= 0.0)) fail("position_margin must be >= 0");
  if (!(velocity_fraction > 0.0 && velocity_fraction <= 1.0)) fail("velocity_fraction must be in (0, 1]");
  if (!(acceleration_fraction > 0.0 && acceleration_fraction <= 1.0)) fail("acceleration_fraction must be in (0, 1]");
  if (!(dt > 0.0)) fail("dt must be > 0");
  // c = a / k >= a dt / 2 keeps the braking set invariant under one period of full braking.
  if (!(approach_rate > 0.0 && approach_rate * dt <= 2.0)) fail("approach_rate must be in (0, 2 / dt]");
  if (!(setpoint_timeout > 0.0)) fail("setpoint_timeout must be > 0");
  if (!(setpoint_periods >= 1.0)) fail("setpoint_periods must be >= 1");
  if (!(max_setpoint_age > 0.0) || !(max_setpoint_lead >= 0.0))
    fail("max_setpoint_age must be > 0 and max_setpoint_lead >= 0");
  if (!(max_setpoint_step > 0.0) || !(max_setpoint_rotation > 0.0)) fail("setpoint step limits must be > 0");
  if (!(max_setpoint_speed > 0.0) || !(max_setpoint_angular_speed > 0.0)) fail("setpoint speed limits must be > 0");
  if (!(max_joint_target_step > 0.0)) fail("max_joint_target_step must be > 0");
  if (!(max_following_error > 0.0)) fail("max_following_error must be > 0");
  if (!(max_force > 0.0) || !(max_torque > 0.0)) fail("force and torque limits must be > 0");
}

SafetyGate::SafetyGate(const SafetyConfig& config) : config_(config) {
  config_.validate();
  n_ = config_.dof();
  ref_ = JointReference{JointVector::Zero(n_), JointVector::Zero(n_), JointVector::Zero(n_)};
  target_q_ = target_qd_ = JointVector::Zero(n_);
  v_max_ = config_.limits.velocity * config_.velocity_fraction;
  a_max_ = config_.max_acceleration * config_.acceleration_fraction;
  c_ = a_max_ / config_.approach_rate;
  state_ = SafetyState::kFault;  // nothing moves before reset()
}

JointVector SafetyGate::reference_lower() const { return config_.limits.lower.array() + config_.position_margin; }
JointVector SafetyGate::reference_upper() const { return config_.limits.upper.array() - config_.position_margin; }

double SafetyGate::braking_speed(int j, double distance) const {
  if (!(distance > 0.0)) return 0.0;
  // sqrt(c^2 + 2 a d) - c, written without cancellation for small d.
  const double a = a_max_[j], c = c_[j];
  return 2.0 * a * distance / (std::sqrt(c * c + 2.0 * a * distance) + c);
}

void SafetyGate::set_state(SafetyState state, std::string reason) {
  if (state == SafetyState::kOk && state_ != SafetyState::kOk) n_intervals_ = next_interval_ = 0, period_ns_ = 0;
  state_ = state;
  reason_ = std::move(reason);
  if (state != SafetyState::kOk) have_target_ = false;
}

std::int64_t SafetyGate::setpoint_loss_timeout_ns() const {
  const auto timeout = static_cast<std::int64_t>(config_.setpoint_timeout * 1e9);
  if (period_ns_ <= 0) return timeout;
  const auto dt = static_cast<std::int64_t>(config_.dt * 1e9);
  return std::min(timeout,
                  static_cast<std::int64_t>(config_.setpoint_periods * static_cast<double>(std::max(period_ns_, dt))));
}

// The period is the longest gap of the window, so a stream's jitter never reads as its loss. The
// gaps are the sender's (its stamps): arrivals bunch up after a delay in the network, which would
// shorten the period and read the next ordinary gap as a loss. Unstamped, several setpoints in one
// servo period are one arrival.
void SafetyGate::learn_period(std::int64_t now_ns, std::int64_t stamp_ns) {
  if (state_ != SafetyState::kOk) return;
  const bool stamped = stamp_ns >= 0 && last_stamp_ns_ >= 0;
  const std::int64_t interval = stamped ? stamp_ns - last_stamp_ns_ : now_ns - last_setpoint_ns_;
  if (interval <= 0) return;
  intervals_[next_interval_] = interval;
  next_interval_ = (next_interval_ + 1) % kPeriodWindow;
  n_intervals_ = std::min(n_intervals_ + 1, kPeriodWindow);
  if (n_intervals_ >= kMinIntervals) period_ns_ = *std::max_element(intervals_, intervals_ + n_intervals_);
}

void SafetyGate::reset(const JointVector& q_measured, std::int64_t now_ns) {
  started_ = true;
  cause_ = FaultCause::kArm;  // (a bad measurement below is the arm's)
  ref_.qd.setZero();
  ref_.qdd.setZero();
  have_target_ = false;
  last_setpoint_ns_ = now_ns;
  in_period_ = 0;
  if (q_measured.size() != n_) {
    set_state(SafetyState::kFault, "reset with " + std::to_string(q_measured.size()) + " joint values for an arm of " +
                                       std::to_string(n_) + " joints");
    return;  // the reference stays where it was: zero velocity, nothing to follow
  }
  if (!q_measured.allFinite()) {
    set_state(SafetyState::kFault, "reset with a non-finite joint measurement");
    return;  // the reference stays where it was: zero velocity, nothing to follow
  }
  ref_.q = q_measured;
  for (int j = 0; j < n_; ++j) {
    if (q_measured[j] < config_.limits.lower[j] || q_measured[j] > config_.limits.upper[j]) {
      set_state(SafetyState::kFault, "reset with joint " + std::to_string(j + 1) +
                                         format(" at %.4f rad, beyond its limits [%.4f, %.4f]", q_measured[j],
                                                config_.limits.lower[j], config_.limits.upper[j]));
      return;
    }
  }
  set_state(SafetyState::kHolding, "waiting for the first setpoint");
}

void SafetyGate::fault(const std::string& reason, FaultCause cause) {
  if (state_ == SafetyState::kFault) return;  // the first reason stays
  cause_ = cause;
  set_state(SafetyState::kFault, reason);
}

bool SafetyGate::clear_input_fault(std::int64_t now_ns) {
  if (!input_fault() || !started_ || ref_.qd.cwiseAbs().maxCoeff() != 0.0) return false;
  last_setpoint_ns_ = now_ns;
  in_period_ = 0;
  set_state(SafetyState::kHolding, "input fault cleared (was: " + reason_ + "); waiting for a setpoint");
  return true;
}

bool SafetyGate::accept_setpoint(std::int64_t now_ns, const SetpointInput& sp, const Eigen::Isometry3d& reference_pose,
                                 Eigen::Isometry3d& pose) {
  if (state_ == SafetyState::kFault) return false;
  if (!finite(sp.position) || !sp.quaternion_xyzw.allFinite() || !finite(sp.linear_velocity) ||
      !finite(sp.angular_velocity)) {
    fault("setpoint rejected: non-finite number (NaN or inf) in its pose or twist", FaultCause::kInput);
    return false;
  }
  const double qn = sp.quaternion_xyzw.norm();
  if (std::abs(qn - 1.0) > 1e-3) {
    fault(format("setpoint rejected: malformed orientation, quaternion norm %.6g (need 1)", qn), FaultCause::kInput);
    return false;
  }
  const double v = sp.linear_velocity.norm(), w = sp.angular_velocity.norm();
  if (v > config_.max_setpoint_speed) {
    fault(format("setpoint rejected: linear speed %.3f m/s above the limit %.3f m/s", v, config_.max_setpoint_speed),
          FaultCause::kInput);
    return false;
  }
  if (w > config_.max_setpoint_angular_speed) {
    fault(format("setpoint rejected: angular speed %.3f rad/s above the limit %.3f rad/s", w,
                 config_.max_setpoint_angular_speed),
          FaultCause::kInput);
    return false;
  }
  const Eigen::Quaterniond q(sp.quaternion_xyzw[3] / qn, sp.quaternion_xyzw[0] / qn, sp.quaternion_xyzw[1] / qn,
                             sp.quaternion_xyzw[2] / qn);
  Eigen::Isometry3d candidate = Eigen::Isometry3d::Identity();
  candidate.linear() = q.toRotationMatrix();
  candidate.translation() = sp.position;

  // A burst (several setpoints in one servo period) is screened as one: each against the
  // setpoint before the period (the arm's position before the first one followed), so small
  // steps cannot add up to a jump within a period.
  const bool following = state_ == SafetyState::kOk;
  const bool burst = in_period_ > 0;
  const Eigen::Isometry3d& from = burst ? period_start_setpoint_ : following ? last_setpoint_ : reference_pose;
  const bool from_arm = burst ? period_start_is_arm_ : !following;
  const auto from_what = [&] {  // (for a fault's reason only: no allocation per setpoint)
    if (!burst) return std::string(from_arm ? "arm's position" : "previous setpoint");
    return format(from_arm ? "arm's position (%.0f setpoints in this servo period)"
                           : "setpoint before this servo period (%.0f setpoints in it)",
                  in_period_ + 1.0);
  };
  const double step = (candidate.translation() - from.translation()).norm();
  if (step > config_.max_setpoint_step) {
    fault(std::string("setpoint rejected: ") + format("%.4f m from the ", step) + from_what() +
              format(" (limit %.4f m)", config_.max_setpoint_step),
          FaultCause::kInput);
    return false;
  }
  const double turn = Eigen::AngleAxisd(Eigen::Matrix3d(candidate.linear() * from.linear().transpose())).angle();
  if (turn > config_.max_setpoint_rotation) {
    fault(std::string("setpoint rejected: ") + format("turned %.4f rad from the ", turn) + from_what() +
              format(" (limit %.4f rad)", config_.max_setpoint_rotation),
          FaultCause::kInput);
    return false;
  }
  learn_period(now_ns, sp.stamp_ns);
  if (!burst) period_start_setpoint_ = from, period_start_is_arm_ = from_arm;
  ++in_period_;
  last_setpoint_ = candidate;
  last_setpoint_ns_ = now_ns;
  last_stamp_ns_ = sp.stamp_ns;
  if (source_ != sp.source) source_.assign(sp.source);  // (reuses its buffer: no allocation per setpoint)
  if (writer_ != sp.writer) writer_.assign(sp.writer);
  if (!following) set_state(SafetyState::kOk, "following setpoints");
  pose = candidate;
  return true;
}

void SafetyGate::set_joint_target(const ArmIkResult& ik, const JointVector& qd_target) {
  if (state_ != SafetyState::kOk) return;
  if (!ik.ok()) {
    fault(std::string("inverse kinematics: ") + robot::to_string(ik.status), FaultCause::kInput);
    return;
  }
  if (ik.q.size() != n_ || qd_target.size() != n_) {
    fault("joint target of " + std::to_string(ik.q.size()) + " joints (velocity " + std::to_string(qd_target.size()) +
          ") for an arm of " + std::to_string(n_));
    return;
  }
  if (!ik.q.allFinite() || !qd_target.allFinite()) {
    fault("non-finite joint target");
    return;
  }
  const JointVector& previous = have_target_ ? target_q_ : ref_.q;
  for (int j = 0; j < n_; ++j) {
    const double jump = std::abs(ik.q[j] - previous[j]);
    if (jump > config_.max_joint_target_step) {
      fault("joint " + std::to_string(j + 1) +
                format(" target jumped %.4f rad in one servo period (limit %.4f rad): an IK branch change?", jump,
                       config_.max_joint_target_step),
            FaultCause::kInput);
      return;
    }
  }
  target_q_ = ik.q;
  target_qd_ = qd_target;
  have_target_ = true;
}

void SafetyGate::check_measured(const JointVector& q, const JointVector& qd) {
  if (state_ == SafetyState::kFault) return;
  if (q.size() != n_ || qd.size() != n_) {
    fault("joint measurement of " + std::to_string(q.size()) + " joints (velocity " + std::to_string(qd.size()) +
          ") for an arm of " + std::to_string(n_));
    return;
  }
  if (!q.allFinite() || !qd.allFinite()) {
    fault("non-finite joint measurement");
    return;
  }
  for (int j = 0; j < n_; ++j) {
    const std::string joint = "joint " + std::to_string(j + 1);
    if (q[j] < config_.limits.lower[j] || q[j] > config_.limits.upper[j]) {
      fault(joint + format(" at %.4f rad, beyond its limits [%.4f, %.4f]", q[j], config_.limits.lower[j],
                           config_.limits.upper[j]));
      return;
    }
    if (std::abs(qd[j]) > config_.limits.velocity[j]) {
      fault(joint + format(" overspeed: %.4f rad/s (limit %.4f rad/s)", qd[j], config_.limits.velocity[j]));
      return;
    }
    const double error = std::abs(q[j] - ref_.q[j]);
    if (error > config_.max_following_error) {
      fault(joint + format(" following error %.4f rad (limit %.4f rad)", error, config_.max_following_error));
      return;
    }
  }
}

void SafetyGate::check_wrench(const Eigen::Vector3d& force, const Eigen::Vector3d& torque) {
  if (state_ == SafetyState::kFault) return;
  if (!force.allFinite() || !torque.allFinite()) {
    fault("non-finite force/torque measurement");
    return;
  }
  if (force.norm() > config_.max_force) {
    fault(format("measured force %.2f N above the limit %.2f N", force.norm(), config_.max_force));
    return;
  }
  if (torque.norm() > config_.max_torque)
    fault(format("measured torque %.3f N m above the limit %.3f N m", torque.norm(), config_.max_torque));
}

const JointReference& SafetyGate::step(std::int64_t now_ns) {
  const double dt = config_.dt;
  if (in_period_ > 1) ++burst_periods_, largest_burst_ = std::max(largest_burst_, in_period_);
  in_period_ = 0;
  if (state_ == SafetyState::kOk && now_ns - last_setpoint_ns_ > setpoint_loss_timeout_ns()) {
    const double silent_ms = static_cast<double>(now_ns - last_setpoint_ns_) * 1e-6;
    const double timeout_ms = static_cast<double>(setpoint_loss_timeout_ns()) * 1e-6;
    std::string why = format("no setpoint for %.0f ms", silent_ms) + (source_.empty() ? "" : " from '" + source_ + "'");
    if (!writer_.empty()) why += " in process '" + writer_ + "'";  // (the lost group, between processes)
    why += period_ns_ > 0 ? format(" (its stream came every %.0f ms; lost after %.0f ms)",
                                   static_cast<double>(period_ns_) * 1e-6, timeout_ms)
                          : format(" (timeout %.0f ms)", timeout_ms);
    // A fault, not a hold: a returning stream is not followed by itself, only after the
    // display's request (clear_input_fault), so it resumes through its own start, not mid-motion.
    fault("setpoint stream lost: " + why + ": held until the display asks", FaultCause::kInput);
  }
  const bool track = started_ && state_ == SafetyState::kOk && have_target_;
  for (int j = 0; j < n_; ++j) {
    const double lo = config_.limits.lower[j] + config_.position_margin;
    const double hi = config_.limits.upper[j] - config_.position_margin;
    const double q = ref_.q[j], v = ref_.qd[j];
    double v_des = 0.0;  // holding: brake to a standstill
    if (track) {
      double qt = target_q_[j], vt = std::clamp(target_qd_[j], -v_max_[j], v_max_[j]);
      if (qt < lo || qt > hi) {  // a target in the margin: go to its edge and stop there
        qt = std::clamp(qt, lo, hi);
        vt = 0.0;
      }
      const double e = qt - q;
      v_des = vt + std::copysign(braking_speed(j, std::abs(e)), e);
    }
    v_des = std::clamp(v_des, -v_max_[j], v_max_[j]);
    // Brake in time for both position limits (a reference already inside a margin, e.g. after a
    // reset there, may only move inwards).
    v_des = std::min(v_des, braking_speed(j, hi - q));
    v_des = std::max(v_des, -braking_speed(j, q - lo));
    // Reach v_des exactly when one period of acceleration allows it (so a stop is exactly 0).
    const double dv_max = a_max_[j] * dt;
    const double v_new = std::abs(v_des - v) <= dv_max ? v_des : v + std::copysign(dv_max, v_des - v);
    const double a = (v_new - v) / dt;
    // Round-off only: the braking curve keeps q inside; never jump into the range from outside.
    const double q_new = std::clamp(q + v_new * dt, std::min(lo, q), std::max(hi, q));
    ref_.q[j] = q_new;
    ref_.qd[j] = v_new;
    ref_.qdd[j] = a;
  }
  return ref_;
}

}  // namespace wysiwyf::robot
