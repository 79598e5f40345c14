#pragma once
// One output data package of the follow program's output recipe (rtde::follow::output_recipe()),
// decoded and checked before the driver believes it: every number finite, the controller's time
// running forward, each mode one the RTDE Guide lists and the status bits within the bits it
// defines. A package that fails is not from a controller (a stream cut short and spliced, a
// damaged peer): the caller refuses it. A state that passes may still say that the arm must hold
// (controller_problem()).
#include <array>
#include <cstdint>
#include <string>

#include "rtde/client_session.hpp"
#include "rtde/follow_program.hpp"
#include "rtde/protocol.hpp"

namespace wysiwyf::robot::ur {

using Six = std::array<double, 6>;

struct UrState {
  double timestamp = 0;  // s since the controller started
  Six q{}, qd{};         // actual_q (rad), actual_qd (rad/s)
  Six current{};         // actual_current: the joint motors' currents, A
  Six moment{};          // target_moment: the joint torques the controller commands, N m
  Six tcp_force{};       // actual_TCP_force: N and N m, base axes, about the TCP; the payload compensated
  rtde::RobotMode robot_mode = rtde::RobotMode::kDisconnected;
  rtde::SafetyMode safety_mode = rtde::SafetyMode::kUndefined;
  rtde::RuntimeState runtime_state = rtde::RuntimeState::kStopped;
  std::uint32_t robot_status_bits = 0, safety_status_bits = 0;
  rtde::follow::ProgramState program = rtde::follow::ProgramState::kNotRunning;
};

// Where each output variable sits in the session's output values (the recipe's order).
class UrStateReader {
 public:
  explicit UrStateReader(const rtde::ClientSession& session);
  // Decodes the session's newest output values into `out`. Returns why they cannot be a
  // controller's (empty when they can); `previous_timestamp` < 0: the first of a connection.
  std::string read(const rtde::ClientSession& session, double previous_timestamp, UrState& out) const;

 private:
  std::size_t timestamp_, q_, qd_, current_, moment_, tcp_force_, robot_mode_, safety_mode_, runtime_state_,
      robot_bits_, safety_bits_, program_;
};

// Why a believable state holds the arm (empty when the follow program may move it): the safety
// system not in NORMAL or REDUCED (a protective stop, an emergency stop, ...), the arm not
// RUNNING (off, brakes on, booting), or the follow program not running.
std::string controller_problem(const UrState& s);
// Whether the follow program runs (holding or following) on a controller whose safety system
// lets it: what recovery waits for.
bool program_running(const UrState& s);

}  // namespace wysiwyf::robot::ur
