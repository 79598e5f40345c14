#include "loop_health.hpp"

#include <algorithm>

#include "summary_json.hpp"

namespace wysiwyf::display {

void LoopHealth::add(const kernel_msgs::Diagnostics& d) {
  Component& c = by_instance_[d.instance().c_str()];
  c.type = d.type().c_str();
  c.rate_hz = d.rate_hz();
  c.tick_rate_hz = d.tick_rate_hz();
  c.tick_p99_us = std::max(c.tick_p99_us, d.tick_time_p99_us());
  c.tick_max_us = std::max(c.tick_max_us, d.tick_time_max_us());
  c.ticks = d.ticks(), c.overruns = d.overruns();
  c.dropped = d.dropped_samples(), c.rejected = d.rejected_samples();
  c.warnings = d.warnings();
}

void LoopHealth::write_json(std::ostream& j) const {
  j << "\"loop_health\": {";
  bool first = true;
  for (const auto& [name, c] : by_instance_) {
    j << (first ? "" : ",") << "\n    " << json_quoted(name) << ": {\"type\": " << json_quoted(c.type)
      << ", \"rate_hz\": " << json_number(c.rate_hz) << ", \"achieved_hz\": " << json_number(c.tick_rate_hz)
      << ", \"tick_p99_us\": " << json_number(c.tick_p99_us) << ", \"tick_max_us\": " << json_number(c.tick_max_us)
      << ", \"ticks\": " << c.ticks << ", \"overruns\": " << c.overruns << ", \"dropped\": " << c.dropped
      << ", \"rejected\": " << c.rejected << ", \"warnings\": " << c.warnings << "}";
    first = false;
  }
  j << (by_instance_.empty() ? "" : "\n  ") << "}";
}

}  // namespace wysiwyf::display
