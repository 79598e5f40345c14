#include "arm_interface/gate_status.hpp"

namespace wysiwyf::robot {

bool GateStatus::publish(std::int64_t now_ns, const SafetyGate& gate, const std::string& source,
                         Output<msg::RobotStatus>& out) {
  const SafetyState state = gate.state();
  const bool changed = last_ns_ < 0 || state != last_state_ || gate.reason() != last_reason_ ||
                       (state == SafetyState::kOk && source != last_source_) || gate.input_fault() != msg_.clearable();
  if (!changed && now_ns - last_ns_ < 100'000'000) return false;
  last_ns_ = now_ns;
  const bool new_fault = changed && state == SafetyState::kFault;
  if (changed) {
    last_state_ = state;
    last_reason_ = gate.reason();
    last_source_ = source;
    switch (state) {
      case SafetyState::kFault: msg_.state(msg::ARM_FAULT); break;
      case SafetyState::kHolding: msg_.state(msg::ARM_HOLDING); break;
      case SafetyState::kOk: msg_.state(msg::ARM_OK); break;
    }
    msg_.source(state == SafetyState::kOk ? source.substr(0, 31) : std::string());
    msg_.reason(gate.reason().substr(0, 255));
  }
  msg_.clearable(gate.input_fault());
  fill_header(msg_.header(), now_ns, seq_++, "base");
  out.write(msg_);
  return new_fault;
}

Health GateStatus::health(const SafetyGate& gate) {
  switch (gate.state()) {
    case SafetyState::kOk: followed_ = true; return Health::kOk;
    case SafetyState::kHolding: return followed_ ? Health::kHolding : Health::kOk;
    case SafetyState::kFault: return Health::kFault;
  }
  return Health::kFault;
}

}  // namespace wysiwyf::robot
