#pragma once
// The driver-level safety layer of an arm of n joints: everything that may command the arm (the
// admittance loop, a script, the user's hand through the display) passes through it on the way to
// the joint servo. One piece of code for the simulated arm (arm_sim) and the real driver.
//
// Every servo period it turns the latest joint target (the inverse kinematics of the interpolated
// Cartesian setpoint) into the joint reference the servo may follow. Whatever the input, that
// reference
//  - stays inside [lower + position_margin, upper - position_margin] (the margin is left for the
//    servo's following error, so the arm itself stays inside its limits);
//  - moves with |velocity| <= velocity_fraction * the velocity limit and |acceleration| <=
//    acceleration_fraction * the acceleration limit: it is a double integrator driven by a bounded
//    acceleration, and its speed towards each position limit never exceeds the braking speed
//    v(d) = sqrt(c^2 + 2 a d) - c (d: distance left, c = a / approach_rate >= a dt / 2), a set
//    that one period of full braking always keeps it in, so it brakes in time for every limit;
//  - approaches a target on that same curve (time-optimal far away, first order with rate
//    approach_rate near it): no overshoot on a still target, no chatter on a moving one;
//  - is never moved by bad input: a non-finite or malformed setpoint, a setpoint jump or speed
//    beyond the limits (a burst of setpoints in one servo period jumps from the setpoint before
//    it: it moves the arm no further than one setpoint may; bursts are counted), an IK failure
//    or branch change, a measured force or torque above its limit, a following error or an
//    overspeed latch a fault with a reason, and the reference brakes to a standstill within the
//    limits and holds there. Faults stay until reset().
//  - When setpoints stop coming it brakes and holds too, latched as an input fault naming the
//    lost source: a stream that comes back is not followed by itself (it may be a frozen process
//    thawing mid-motion), only once the display asks (clear_input_fault). The stream is lost
//    after setpoint_periods of its own period (learned from the stamps of its last setpoints, so a
//    burst of late deliveries does not shorten it: 3 ms for a 1 kHz stream, 60 ms for a 50 Hz
//    one), at most setpoint_timeout.
//  - A fault that bad input caused (a setpoint refused above, an unreachable or jumping IK
//    target, the stream lost) may be cleared once the reference is at rest (clear_input_fault:
//    the supervisor's request once its inputs are good again); then the first setpoint within
//    max_setpoint_step of where the arm stands starts it again. A fault of the arm itself
//    (limits, overspeed, following error, force, a bad measurement) stays until reset().
#include <cstdint>
#include <string>
#include <string_view>

#include <Eigen/Geometry>

#include "arm_model/arm_ik.hpp"
#include "arm_model/arm_types.hpp"

namespace wysiwyf::robot {

struct SafetyConfig {
  ArmLimits limits;                         // hard position and velocity limits of the n joints (effort unused)
  JointVector max_acceleration;             // hard acceleration limits, n values [rad/s^2]
  double position_margin = 0.02;            // rad kept between the reference and each limit
  double velocity_fraction = 0.9;           // of the velocity limits, for the reference
  double acceleration_fraction = 0.8;       // of the acceleration limits, for the reference
  double approach_rate = 50.0;              // 1/s: first-order rate of the final approach
  double dt = 1e-3;                         // servo period [s]
  double setpoint_timeout = 0.06;           // s without a setpoint before braking to a hold, at most
  double setpoint_periods = 3.0;            // the stream's own periods without a setpoint: lost
  double max_setpoint_age = 0.05;           // s: a setpoint stamped longer ago is stale (refused)
  double max_setpoint_lead = 0.005;         // s: one stamped further ahead is from the future (refused)
  double max_setpoint_step = 0.1;           // m between consecutive setpoints
  double max_setpoint_rotation = 0.5;       // rad between consecutive setpoints
  double max_setpoint_speed = 2.0;          // m/s in a setpoint's twist
  double max_setpoint_angular_speed = 6.0;  // rad/s in a setpoint's twist
  double max_joint_target_step = 0.2;       // rad per servo period (an IK branch change)
  double max_following_error = 0.1;         // rad between the reference and the measurement
  double max_force = 100.0;                 // N, norm of the measured force
  double max_torque = 10.0;                 // N m, norm of the measured torque

  // The number of joints (that of the position limits).
  int dof() const { return static_cast<int>(limits.lower.size()); }
  // Throws std::invalid_argument naming the first value that does not fit (every per-joint list
  // must hold n = dof() values, 1 <= n <= kMaxArmDof).
  void validate() const;
};

enum class SafetyState {
  kOk,       // following setpoints
  kHolding,  // braking to, or holding, a standstill: no setpoint yet (or since a fault was cleared)
  kFault,    // latched: braking to, or holding, a standstill until cleared or reset()
};
const char* to_string(SafetyState state);

// What latched a fault: bad input (a setpoint, or the stream's loss), which the supervisor may
// clear once its input is good again, or the arm itself (a measurement out of bounds), which only
// reset() clears.
enum class FaultCause { kInput, kArm };

// A Cartesian setpoint as it arrived (base_T_dev and its twist in base coordinates), unchecked.
struct SetpointInput {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector4d quaternion_xyzw = Eigen::Vector4d(0, 0, 0, 1);
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  std::string_view source;  // who sent it (named when its stream is lost)
  std::string_view writer;  // the process that sent it, from another one ("demo-hosts/display/4711"), else empty
  // The sender's stamp (its clock), from which the stream's period is learned: a delivery burst
  // (samples held up in a network, then arriving one per servo period) does not shorten it. -1:
  // not known, the period is learned from the arrivals.
  std::int64_t stamp_ns = -1;
};

struct JointReference {
  JointVector q;
  JointVector qd;
  JointVector qdd;  // the acceleration of the last step
};

class SafetyGate {
 public:
  explicit SafetyGate(const SafetyConfig& config);  // validates it

  // Starts (again) from the measured joints, taken to be at rest: clears any fault, the reference
  // is q_measured with zero velocity, the state is kHolding until the first setpoint. A
  // non-finite q_measured, one of another joint count or one beyond the hard limits is a fault at
  // once.
  void reset(const JointVector& q_measured, std::int64_t now_ns);

  // A setpoint as it arrives. Returns true and sets `pose` (quaternion normalised) when it may be
  // followed; false when the gate is faulted, or when the setpoint is bad (then it faults):
  // non-finite numbers, a quaternion whose norm is not 1 (+-1e-3), a twist above the speed limits,
  // or a jump from the previous setpoint (from `reference_pose`, the pose of the reference, when
  // not following yet) above max_setpoint_step / max_setpoint_rotation. Feeds the watchdog.
  bool accept_setpoint(std::int64_t now_ns, const SetpointInput& setpoint, const Eigen::Isometry3d& reference_pose,
                       Eigen::Isometry3d& pose);

  // While following, every servo period: the IK of the interpolated setpoint and the target's
  // joint velocity. An IK failure, a non-finite target, one of another joint count or a jump of
  // more than max_joint_target_step from the previous target (from the reference, for the first
  // one) is a fault. Ignored unless following.
  void set_joint_target(const ArmIkResult& ik, const JointVector& qd_target);

  // The measured joints (checked against the hard limits, the velocity limits and the following
  // error to the last reference) and the measured force/torque. Out of bounds, non-finite or of
  // another joint count: fault.
  void check_measured(const JointVector& q, const JointVector& qd);
  void check_wrench(const Eigen::Vector3d& force, const Eigen::Vector3d& torque);

  // Latches a fault (the first reason and cause are kept until reset()).
  void fault(const std::string& reason, FaultCause cause = FaultCause::kArm);
  // Clears a fault that bad input caused, once the reference has braked to a standstill: the gate
  // then holds until a setpoint near the arm comes. Returns false (and changes nothing) for a
  // fault of the arm, while still braking, or when there is no fault.
  bool clear_input_fault(std::int64_t now_ns);
  bool input_fault() const { return state_ == SafetyState::kFault && cause_ == FaultCause::kInput; }

  // Advances the reference by one servo period (also runs the watchdog).
  const JointReference& step(std::int64_t now_ns);

  SafetyState state() const { return state_; }
  bool following() const { return state_ == SafetyState::kOk; }
  // "following setpoints", "waiting for the first setpoint", or the fault's reason ("setpoint
  // stream lost: no setpoint for 61 ms from 'script' ...").
  const std::string& reason() const { return reason_; }
  const JointReference& reference() const { return ref_; }
  // The setpoint stream's period, learned from its last setpoints' stamps (their arrivals when
  // unstamped): the longest of the last kPeriodWindow intervals; 0 while unknown (fewer than
  // kMinIntervals since following began: two samples bunched at the start say little).
  std::int64_t setpoint_period_ns() const { return period_ns_; }
  // Rate bursts: servo periods that brought more than one setpoint (a network's bunching, or a
  // sender writing faster than its stream), and the most one brought. Each of a burst is screened
  // against the setpoint before its period, so a burst moves the arm no further than one setpoint.
  std::uint64_t burst_periods() const { return burst_periods_; }
  int largest_burst() const { return largest_burst_; }
  // How long the stream may be silent before the gate faults and brakes: setpoint_periods of its
  // period (of the servo period at least), at most setpoint_timeout, which alone applies while
  // the period is unknown.
  std::int64_t setpoint_loss_timeout_ns() const;
  const SafetyConfig& config() const { return config_; }
  // The bounds the reference keeps (hard limits scaled by the fractions, margin applied).
  const JointVector& reference_velocity_limit() const { return v_max_; }
  const JointVector& reference_acceleration_limit() const { return a_max_; }
  JointVector reference_lower() const;
  JointVector reference_upper() const;
  // Largest speed at which the reference may approach a point `distance` away on joint j.
  double braking_speed(int j, double distance) const;

 private:
  void set_state(SafetyState state, std::string reason);
  void learn_period(std::int64_t now_ns, std::int64_t stamp_ns);

  static constexpr int kPeriodWindow = 8;
  static constexpr int kMinIntervals = 4;

  SafetyConfig config_;
  int n_ = 0;  // joints
  JointVector v_max_, a_max_, c_;
  SafetyState state_ = SafetyState::kHolding;
  std::string reason_ = "not started (reset() not called)";
  JointReference ref_;
  bool started_ = false;
  FaultCause cause_ = FaultCause::kArm;
  std::int64_t last_setpoint_ns_ = 0;
  std::int64_t last_stamp_ns_ = -1;             // the sender's stamp of the last accepted setpoint
  std::string source_;                          // of the last accepted setpoint
  std::string writer_;                          // its process, when another one
  std::int64_t intervals_[kPeriodWindow] = {};  // between the last setpoints' stamps (arrivals), ns
  int n_intervals_ = 0, next_interval_ = 0;
  std::int64_t period_ns_ = 0;
  Eigen::Isometry3d last_setpoint_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d period_start_setpoint_ = Eigen::Isometry3d::Identity();  // the jump checks' origin in a burst
  bool period_start_is_arm_ = false;  // (the first of the period was checked against the arm)
  int in_period_ = 0;                 // setpoints accepted this servo period
  std::uint64_t burst_periods_ = 0;
  int largest_burst_ = 0;
  bool have_target_ = false;
  JointVector target_q_;
  JointVector target_qd_;
};

}  // namespace wysiwyf::robot
