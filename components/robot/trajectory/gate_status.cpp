#include "trajectory/gate_status.hpp"

namespace wysiwyf::robot {

bool GateStatus::update(std::int64_t now_ns, const SafetyGate& gate, const std::string& source, msg::RobotStatus& out) {
  const SafetyState state = gate.state();
  const bool changed =
      last_ns_ < 0 || state != last_state_ || gate.reason() != last_reason_ || (state == SafetyState::kOk && source != last_source_);
  new_fault_ = false;
  if (!changed && now_ns - last_ns_ < 100'000'000) return false;
  last_ns_ = now_ns;
  if (changed) {
    new_fault_ = state == SafetyState::kFault;
    last_state_ = state;
    last_reason_ = gate.reason();
    last_source_ = source;
    switch (state) {
      case SafetyState::kFault: out.state(msg::ARM_FAULT); break;
      case SafetyState::kHolding: out.state(msg::ARM_HOLDING); break;
      case SafetyState::kOk: out.state(msg::ARM_OK); break;
    }
    out.source(state == SafetyState::kOk ? source.substr(0, 31) : std::string());
    out.reason(gate.reason().substr(0, 127));
  }
  out.header().stamp_ns(now_ns);
  out.header().seq(seq_++);
  out.header().frame_id("base");
  return true;
}

}  // namespace wysiwyf::robot
