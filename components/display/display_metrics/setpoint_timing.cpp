#include "setpoint_timing.hpp"

#include "summary_json.hpp"

namespace wysiwyf::display {

void SetpointTiming::add_setpoint(const std::string& source, std::int64_t t, const Eigen::Vector3d& position,
                                  const Eigen::Vector3d& velocity, std::int64_t sensed_ns) {
  lag_.setpoint(t, position, velocity);
  unanswered_.push_back({source, t, sensed_ns});
}

void SetpointTiming::answer_setpoints() {
  for (const auto& s : unanswered_) sensed_.setpoint(s.source, s.stamp, s.sensed);
  unanswered_.clear();
}

std::vector<std::string> SetpointTiming::end_lines() const {
  std::vector<std::string> lines;
  if (lag_.lag_ms().samples() > 0)
    lines.push_back("setpoint to motion: the plate reaches a moving setpoint p50 " +
                    std::to_string(lag_.lag_ms().percentile(50)) + " ms, p99 " +
                    std::to_string(lag_.lag_ms().percentile(99)) + " ms after it was made (" +
                    std::to_string(lag_.lag_ms().samples()) + " setpoints; " + std::to_string(lag_.not_reached()) +
                    " not reached)");
  for (const auto& [sensor, ms] : sensed_.by_sensor())
    lines.push_back("sensor sample to setpoint (" + sensor + "): p50 " + std::to_string(ms.percentile(50)) +
                    " ms, p99 " + std::to_string(ms.percentile(99)) + " ms, max " + std::to_string(ms.max()) +
                    " ms over " + std::to_string(ms.samples()) + " samples");
  return lines;
}

void SetpointTiming::write_json(std::ostream& j) const {
  j << "\"setpoint_to_motion\": {\"setpoints\": " << lag_.lag_ms().samples()
    << ", \"not_reached\": " << lag_.not_reached() << ", " << json_figures(lag_.lag_ms(), "ms")
    << "},\n  \"sensor_to_setpoint\": {";
  bool first = true;
  for (const auto& [sensor, ms] : sensed_.by_sensor()) {
    j << (first ? "" : ",") << "\n    " << json_quoted(sensor) << ": {\"samples\": " << ms.samples() << ", "
      << json_figures(ms, "ms") << "}";
    first = false;
  }
  j << (first ? "" : "\n  ") << "}";
}

}  // namespace wysiwyf::display
