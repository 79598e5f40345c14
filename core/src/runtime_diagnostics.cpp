// The executor's diagnostics: one kernel_msgs::Diagnostics per component on wysiwyf/diagnostics.
#include "runtime_impl.hpp"
#include "wysiwyf/kernel_msgs.hpp"

namespace wysiwyf {

using kernel_msgs::ComponentState;

void Runtime::Impl::publish_diagnostics(Time now, double window_s, bool final) {
  for (auto& slot : slots) {
    const auto s = slot->stats.summarise();
    auto& d = diag_msg;
    fill_header(d.header(), now.ns, slot->diag_seq++, "");
    d.instance(slot->spec->name);
    d.type(slot->spec->type.value);
    d.process(slot->spec->process_name());
    d.rate_hz(slot->spec->rate.value);
    d.tick_rate_hz(window_s > 0 ? static_cast<double>(s.window_ticks) / window_s : 0.0);
    d.tick_time_p50_us(s.p50_us);
    d.tick_time_p99_us(s.p99_us);
    d.tick_time_max_us(s.max_us);
    d.tick_late_p50_us(s.late_p50_us);
    d.tick_late_p99_us(s.late_p99_us);
    d.tick_late_max_us(s.late_max_us);
    d.ticks(s.ticks);
    d.overruns(s.overruns);
    d.dropped_samples(slot->dropped());
    d.dropped_by_port().clear();
    for (const auto& [port, queue] : slot->inputs_by_port)
      if (queue->dropped() > 0 && d.dropped_by_port().size() < 32) {
        kernel_msgs::PortCount c;
        c.port(port.substr(0, 63));
        c.count(queue->dropped());
        d.dropped_by_port().push_back(c);
      }
    {  // what the component reported, read at once (not held while writing: its thread may report)
      std::lock_guard<std::mutex> lock(slot->health_mutex);
      d.state(!slot->last_error.empty() || slot->health == Health::kFault ? ComponentState::STATE_FAULT
              : slot->health == Health::kHolding                          ? ComponentState::STATE_HOLDING
              : final                                                     ? ComponentState::STATE_STOPPED
              : slot->stage == Slot::Stage::kActive                       ? ComponentState::STATE_ACTIVE
                                                                          : ComponentState::STATE_CONFIGURED);
      d.rejected_samples(slot->rejected);
      d.warnings(slot->warnings);
      d.last_warning(slot->last_warning.substr(0, 255));
      d.last_error((slot->last_error.empty() ? slot->health_reason : slot->last_error).substr(0, 255));
    }
    diagnostics.write(d);
  }
}

}  // namespace wysiwyf
