#include "trajectory/gate_status.hpp"

namespace wysiwyf::robot {

bool GateStatus::update(std::int64_t now_ns, const SafetyGate& gate, const std::string& source, msg::DisplayMode& out) {
  const SafetyState state = gate.state();
  const bool changed = last_ns_ < 0 || state != last_state_ || gate.reason() != last_reason_;
  new_fault_ = false;
  if (!changed && now_ns - last_ns_ < 100'000'000) return false;
  last_ns_ = now_ns;
  if (changed) {
    new_fault_ = state == SafetyState::kFault;
    last_state_ = state;
    last_reason_ = gate.reason();
    switch (state) {
      case SafetyState::kFault: out.mode(msg::MODE_FAULT); break;
      case SafetyState::kHolding: out.mode(msg::MODE_IDLE); break;
      case SafetyState::kOk: out.mode(source == "admittance" ? msg::MODE_ADMITTANCE : msg::MODE_SURFACE); break;
    }
    std::string reason = std::string(to_string(state)) + ": " + gate.reason();
    if (state == SafetyState::kOk) reason += " (source '" + source + "')";
    if (reason.size() > 127) reason.resize(127);
    out.reason(reason);
  }
  out.header().stamp_ns(now_ns);
  out.header().seq(seq_++);
  out.header().frame_id("base");
  return true;
}

}  // namespace wysiwyf::robot
