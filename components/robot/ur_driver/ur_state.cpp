#include "ur_state.hpp"

#include <cmath>

namespace wysiwyf::robot::ur {
namespace {

using rtde::follow::ProgramState;

// The RTDE Guide's ranges: robot_mode -1..8, safety_mode 1..13, runtime_state 0..5; the bits
// robot_status_bits (0..3: power on, program running, teach button, power button) and
// safety_status_bits (0..10) define.
constexpr std::int32_t kRobotModeFirst = -1, kRobotModeLast = 8;
constexpr std::int32_t kSafetyModeFirst = 1, kSafetyModeLast = 13;
constexpr std::uint32_t kRuntimeStateLast = 5;
constexpr std::uint32_t kRobotStatusMask = 0xF, kSafetyStatusMask = 0x7FF;
constexpr std::int32_t kProgramStateLast = static_cast<std::int32_t>(ProgramState::kStoppedHostLost);

bool finite(const Six& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

UrStateReader::UrStateReader(const rtde::ClientSession& s)
    : timestamp_(s.output_index("timestamp")),
      q_(s.output_index("actual_q")),
      qd_(s.output_index("actual_qd")),
      current_(s.output_index("actual_current")),
      moment_(s.output_index("target_moment")),
      tcp_force_(s.output_index("actual_TCP_force")),
      robot_mode_(s.output_index("robot_mode")),
      safety_mode_(s.output_index("safety_mode")),
      runtime_state_(s.output_index("runtime_state")),
      robot_bits_(s.output_index("robot_status_bits")),
      safety_bits_(s.output_index("safety_status_bits")),
      program_(s.output_index(rtde::follow::kProgramState)) {}

std::string UrStateReader::read(const rtde::ClientSession& session, double previous_timestamp, UrState& out) const {
  const rtde::RecipeValues& v = session.outputs();
  UrState s;
  s.timestamp = v.get_double(timestamp_);
  s.q = v.get_vector6d(q_), s.qd = v.get_vector6d(qd_);
  s.current = v.get_vector6d(current_), s.moment = v.get_vector6d(moment_);
  s.tcp_force = v.get_vector6d(tcp_force_);
  const std::int32_t robot_mode = v.get_int32(robot_mode_), safety_mode = v.get_int32(safety_mode_);
  const std::uint32_t runtime = v.get_uint32(runtime_state_);
  s.robot_status_bits = v.get_uint32(robot_bits_), s.safety_status_bits = v.get_uint32(safety_bits_);
  const std::int32_t program = v.get_int32(program_);

  if (!std::isfinite(s.timestamp) || s.timestamp < 0) return "timestamp " + std::to_string(s.timestamp) + " s";
  if (previous_timestamp >= 0 && !(s.timestamp > previous_timestamp))
    return "timestamp " + std::to_string(s.timestamp) + " s, not after the previous package's " +
           std::to_string(previous_timestamp) + " s";
  if (!finite(s.q) || !finite(s.qd) || !finite(s.current) || !finite(s.moment) || !finite(s.tcp_force))
    return "a non-finite joint angle, velocity, current, torque or TCP force";
  if (robot_mode < kRobotModeFirst || robot_mode > kRobotModeLast)
    return "robot_mode " + std::to_string(robot_mode) + ", expected -1 to 8";
  if (safety_mode < kSafetyModeFirst || safety_mode > kSafetyModeLast)
    return "safety_mode " + std::to_string(safety_mode) + ", expected 1 to 13";
  if (runtime > kRuntimeStateLast) return "runtime_state " + std::to_string(runtime) + ", expected 0 to 5";
  if ((s.robot_status_bits & ~kRobotStatusMask) != 0 || (s.safety_status_bits & ~kSafetyStatusMask) != 0)
    return "status bits " + std::to_string(s.robot_status_bits) + "/" + std::to_string(s.safety_status_bits) +
           " beyond the bits RTDE defines (0..3 and 0..10)";
  if (program < 0 || program > kProgramStateLast)
    return std::string(rtde::follow::kProgramState) + " " + std::to_string(program) + ", expected 0 to " +
           std::to_string(kProgramStateLast) + " (the follow program's states)";
  s.robot_mode = static_cast<rtde::RobotMode>(robot_mode);
  s.safety_mode = static_cast<rtde::SafetyMode>(safety_mode);
  s.runtime_state = static_cast<rtde::RuntimeState>(runtime);
  s.program = static_cast<ProgramState>(program);
  out = s;
  return {};
}

std::string controller_problem(const UrState& s) {
  if (s.safety_mode != rtde::SafetyMode::kNormal && s.safety_mode != rtde::SafetyMode::kReduced)
    return "the safety system reports " + std::string(rtde::to_string(s.safety_mode)) + " (safety_mode " +
           std::to_string(static_cast<int>(s.safety_mode)) + ")";
  if (s.robot_mode != rtde::RobotMode::kRunning)
    return "the arm is not running: robot_mode " + std::string(rtde::to_string(s.robot_mode)) +
           " (power it on and release the brakes on the pendant)";
  switch (s.program) {
    case ProgramState::kFollowing:
    case ProgramState::kHolding: return {};
    case ProgramState::kNotRunning:
      return "the follow program is not running (" + std::string(rtde::follow::kProgramState) + " = 0, runtime_state " +
             std::string(rtde::to_string(s.runtime_state)) + ")";
    case ProgramState::kStoppedHostLost:
      return "the follow program stopped itself: it saw no new counter for " +
             std::to_string(rtde::follow::kWatchdogPeriods) + " periods (" + rtde::follow::kProgramState + " = 3)";
  }
  return "unknown program state";
}

bool program_running(const UrState& s) { return controller_problem(s).empty(); }

}  // namespace wysiwyf::robot::ur
