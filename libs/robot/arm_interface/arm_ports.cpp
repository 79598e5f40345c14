#include "arm_interface/arm_ports.hpp"

#include <tuple>
#include <type_traits>
#include <utility>

#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot {
namespace {

// A JointState field (position, velocity, effort): a std::array of the IDL's fixed joint count,
// or a bounded sequence (a std::vector) resized to the arm's.
using JointField = std::remove_reference_t<decltype(std::declval<msg::JointState&>().position())>;

template <class Field, class = void>
struct IsSequence : std::false_type {};
template <class Field>
struct IsSequence<Field, std::void_t<decltype(std::declval<Field&>().resize(1))>> : std::true_type {};

// The fixed joint count of an array field (0 for a sequence).
template <class Field>
constexpr int fixed_joints() {
  if constexpr (IsSequence<Field>::value)
    return 0;
  else
    return static_cast<int>(std::tuple_size<Field>::value);
}

// Writes v into the field (sized to v's joints; a sequence keeps its buffer: no allocation per tick).
template <class Field>
void put(Field& field, const JointVector& v) {
  if constexpr (IsSequence<Field>::value) field.resize(static_cast<std::size_t>(v.size()));
  for (int j = 0; j < v.size(); ++j) field[static_cast<std::size_t>(j)] = v[j];
}

}  // namespace

bool joint_state_carries(int n) {
  if constexpr (IsSequence<JointField>::value) return n >= 1 && n <= kMaxArmDof;
  return n == fixed_joints<JointField>();
}

std::string joint_state_capacity() {
  if constexpr (IsSequence<JointField>::value) return "1 to " + std::to_string(kMaxArmDof) + " joints";
  return "exactly " + std::to_string(fixed_joints<JointField>()) + " joints (interfaces/msgs/sensor_msgs.idl)";
}

void ArmPorts::declare(Context& ctx, Report report) {
  report_ = std::move(report);
  setpoint = ctx.input<msg::CartesianSetpoint>(
      "setpoint", "base_T_dev and its twist, at any period of 1-20 ms (one writer: a second is a validation error)",
      Qos::reliable(32).one_writer());
  request = ctx.input<msg::ArmRequest>(
      "request",
      "the supervisor's requests: CLEAR_INPUT_FAULT once its inputs are good again (optional; one writer, the "
      "setpoint's)",
      Qos::reliable(8).optional_input().one_writer());
  joint_state_out_ =
      ctx.output<msg::JointState>("joint_state", "measured joint angles (encoders), velocities, motor torques");
  device_pose_out_ = ctx.output<msg::PoseStamped>("device_pose", "base_T_dev by FK of the measured joints");
  status_out_ = ctx.output<msg::RobotStatus>(
      "status", "safety state (RobotStatus): ok following a source, holding, or fault, with the reason",
      Qos{Reliability::kReliable, Durability::kTransientLocal, 4, 0});
}

namespace {
// A writer's process group: its DDS participant's name "<pipeline>/<group>/<pid>" without the pid
// (a restarted process of the group is the same writer); "" for this process.
std::string group_of(const std::string& writer) {
  const auto slash = writer.rfind('/');
  if (slash == std::string::npos || slash + 1 == writer.size() || writer.find('/') == slash) return writer;
  for (std::size_t i = slash + 1; i < writer.size(); ++i)
    if (writer[i] < '0' || writer[i] > '9') return writer;
  return writer.substr(0, slash);
}
}  // namespace

void ArmPorts::take_setpoints(const ArmParams& params, SetpointFollower& follower, std::int64_t now_ns) {
  while (setpoint.take(setpoint_msg_)) {
    setpoint_group_ = group_of(setpoint.writer());  // (the topic's one writer: DDS refused any other)
    if (const std::string why = params.source_problem(setpoint_msg_); !why.empty()) {
      report_.reject_setpoint(setpoint, why);
      continue;
    }
    if (follower.take(setpoint_msg_, now_ns, setpoint.writer()) == SetpointFollower::Taken::kRefused)
      report_.reject_setpoint(setpoint, follower.refusal());
  }
}

void ArmPorts::take_requests(SafetyGate& gate, std::int64_t now_ns) {
  while (request.take(request_msg_)) {
    if (const std::string group = group_of(request.writer()); group != setpoint_group_) {
      report_.reject_request(request,
                             "from " + (group.empty() ? std::string("this process") : "'" + group + "'") +
                                 ", not from the setpoint's writer (" +
                                 (setpoint_group_.empty() ? std::string("this process") : "'" + setpoint_group_ + "'") +
                                 "): only what drives the arm may clear its faults");
      continue;
    }
    if (request_msg_.request() != msg::ARM_CLEAR_INPUT_FAULT) {
      report_.reject_request(request, "unknown request " + std::to_string(static_cast<int>(request_msg_.request())));
      continue;
    }
    const std::string was = gate.reason();
    if (gate.clear_input_fault(now_ns))
      report_.log("cleared the input fault '" + was + "' as asked: " + request_msg_.reason().c_str());
    else if (gate.state() != SafetyState::kFault)
      continue;  // (already cleared: a request in flight)
    else
      report_.reject_request(request, gate.input_fault()
                                          ? "still braking: ask again once the arm stands still"
                                          : "the fault is the arm's own, only a restart clears it: " + was);
  }
}

void ArmPorts::log_bursts(const SafetyGate& gate) {
  if (gate.burst_periods() == 0) return;
  report_.log("setpoint bursts: " + std::to_string(gate.burst_periods()) +
              " servo period(s) brought more than one setpoint (at most " + std::to_string(gate.largest_burst()) +
              "); each was screened against the setpoint before its period");
}

void ArmPorts::publish_measurement(std::int64_t stamp_ns, std::uint64_t seq, const JointVector& q,
                                   const JointVector& qd, const JointVector& effort, const std::string& tip_frame,
                                   const Eigen::Isometry3d& base_T_tip) {
  fill_header(joint_msg_.header(), stamp_ns, seq, "base");
  put(joint_msg_.position(), q);
  put(joint_msg_.velocity(), qd);
  put(joint_msg_.effort(), effort);
  joint_state_out_.write(joint_msg_);
  fill_header(pose_msg_.header(), stamp_ns, seq, "base");
  pose_msg_.child_frame_id(tip_frame);
  msgs::to_msg(base_T_tip, pose_msg_.pose());
  device_pose_out_.write(pose_msg_);
}

}  // namespace wysiwyf::robot
