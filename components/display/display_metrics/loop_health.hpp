#pragma once
// Loop health, from the kernel's per-component diagnostics: per component, its configured and
// achieved rate, the worst tick p99 and max over the windows, its ticks, overruns, dropped and
// rejected samples and warnings (the latest counts).
#include <cstdint>
#include <map>
#include <ostream>
#include <string>

#include "wysiwyf/kernel_msgs.hpp"

namespace wysiwyf::display {

class LoopHealth {
 public:
  void add(const kernel_msgs::Diagnostics& d);
  // The summary's "loop_health" member.
  void write_json(std::ostream& j) const;

 private:
  struct Component {
    std::string type;
    double rate_hz = 0, tick_rate_hz = 0, tick_p99_us = 0, tick_max_us = 0;
    std::uint64_t ticks = 0, overruns = 0, dropped = 0, rejected = 0, warnings = 0;
  };
  std::map<std::string, Component> by_instance_;
};

}  // namespace wysiwyf::display
