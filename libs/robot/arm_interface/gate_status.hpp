#pragma once
// The arm's safety status as a RobotStatus message: ARM_FAULT with the reason, ARM_HOLDING, or
// ARM_OK following the setpoints' source. Sent on every change and repeated every 100 ms; the
// repeats reuse the message (no allocation).
#include <cstdint>
#include <string>

#include "safety_gate/safety_gate.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"
#include "wysiwyf/port.hpp"

namespace wysiwyf::robot {

class GateStatus {
 public:
  // Writes the status to `out` when one is due at now_ns; returns true when a fault (or another
  // fault reason) has just appeared, for the caller's log.
  bool publish(std::int64_t now_ns, const SafetyGate& gate, const std::string& source, Output<msg::RobotStatus>& out);
  // The gate as the component's health (Component::report_health): a fault is kFault; holding
  // after it has followed setpoints (the stream stopped) is kHolding; following, or waiting for
  // the first setpoint, is kOk.
  Health health(const SafetyGate& gate);

 private:
  msg::RobotStatus msg_;
  SafetyState last_state_ = SafetyState::kFault;
  std::string last_reason_, last_source_;
  std::int64_t last_ns_ = -1;
  std::uint64_t seq_ = 0;
  bool followed_ = false;
};

}  // namespace wysiwyf::robot
