#pragma once
// The kernel's view of a Context after configure(): what the component declared, and its input
// queues in run mode. Components see none of this (context.hpp keeps it private).
#include <map>
#include <string>
#include <vector>

#include "wysiwyf/context.hpp"

namespace wysiwyf::detail {

struct ContextAccess {
  static const std::vector<ParamSpec>& declared_params(const Context& c) { return c.params_; }
  static const std::vector<PortSpec>& declared_ports(const Context& c) { return c.ports_; }
  static const std::string& summary_text(const Context& c) { return c.summary_; }
  // Run mode: the queues of the component's inputs, for the kernel's diagnostics.
  static const std::vector<const QueueCounters*>& input_queues(const Context& c) { return c.input_queues_; }
  // Run mode: the queue of each input port, by port name (per-port diagnostics).
  static const std::map<std::string, QueueCounters*>& input_queues_by_port(const Context& c) {
    return c.input_by_port_;
  }
  // Run mode: the queue of one input port (for a trigger's doorbell); nullptr when none.
  static QueueCounters* input_queue(const Context& c, const std::string& port) {
    const auto it = c.input_by_port_.find(port);
    return it == c.input_by_port_.end() ? nullptr : it->second;
  }
};

}  // namespace wysiwyf::detail
