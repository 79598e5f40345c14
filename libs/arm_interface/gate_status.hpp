#pragma once
// The arm's safety status as a RobotStatus message: ARM_FAULT with the reason, ARM_HOLDING, or
// ARM_OK following the setpoints' source. Sent on every change and repeated every 100 ms; the
// repeats reuse the message (no allocation).
#include <cstdint>
#include <string>

#include "safety_gate/safety_gate.hpp"
#include "wysiwyf/msgs.hpp"
#include "wysiwyf/port.hpp"

namespace wysiwyf::robot {

class GateStatus {
 public:
  // Writes the status to `out` when one is due at now_ns; returns true when a fault (or another
  // fault reason) has just appeared, for the caller's log.
  bool publish(std::int64_t now_ns, const SafetyGate& gate, const std::string& source, Output<msg::RobotStatus>& out);

 private:
  msg::RobotStatus msg_;
  SafetyState last_state_ = SafetyState::kFault;
  std::string last_reason_, last_source_;
  std::int64_t last_ns_ = -1;
  std::uint64_t seq_ = 0;
};

}  // namespace wysiwyf::robot
