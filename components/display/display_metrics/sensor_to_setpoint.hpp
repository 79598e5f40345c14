#pragma once
// Sensor sample to setpoint: how long after the sensor sample it answers (CartesianSetpoint's
// sensed_ns: the wrist wrench in admittance display, the hand's position in surface display) each
// setpoint was made, per source. Setpoints that answer no sample (holds, scripts) are not counted.
#include <cstdint>
#include <map>
#include <string>

#include "stats/percentiles.hpp"

namespace wysiwyf::display {

class SensorToSetpoint {
 public:
  void setpoint(const std::string& source, std::int64_t stamp_ns, std::int64_t sensed_ns) {
    if (sensed_ns <= 0) return;
    by_source_[source].add(static_cast<double>(stamp_ns - sensed_ns) * 1e-6, stamp_ns);
  }
  // source -> latency in ms
  const std::map<std::string, stats::Percentiles>& by_source() const { return by_source_; }

 private:
  std::map<std::string, stats::Percentiles> by_source_;
};

}  // namespace wysiwyf::display
