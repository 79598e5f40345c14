#pragma once
// Sensor sample to setpoint: for each sensor sample, how long until the first setpoint answering
// it or a newer sample (CartesianSetpoint's sensed_ns) was made. The wrist wrench answers in
// admittance display, the hand's position in surface display (the source's last word says which).
// With the sensor's samples (`sample`), every sample of a run of setpoints from one source
// counts: a physics step every 20 ms answers 20 wrench samples, 1 to 20 ms after each. Without
// them, or at the first setpoint of a run, only the answered sample counts. Setpoints answering
// none (holds, scripts: sensed_ns 0) break the run and are not counted.
#include <cstdint>
#include <deque>
#include <map>
#include <string>

#include "stats/percentiles.hpp"

namespace wysiwyf::display {

class SensorToSetpoint {
 public:
  // "wrench" for a source ending in "admittance", "hand" for one ending in "surface", else the source.
  static std::string sensor_of(const std::string& source);

  void sample(const std::string& sensor, std::int64_t t_ns);
  void setpoint(const std::string& source, std::int64_t stamp_ns, std::int64_t sensed_ns);

  // sensor -> latency in ms
  const std::map<std::string, stats::Percentiles>& by_sensor() const { return by_sensor_; }

 private:
  struct Stream {
    std::deque<std::int64_t> samples;  // not answered yet, oldest first
    std::int64_t answered = 0;         // the newest sample answered
  };
  std::map<std::string, Stream> streams_;
  std::map<std::string, stats::Percentiles> by_sensor_;
  std::string run_;  // the source of the previous setpoint ("" after one answering nothing)
};

}  // namespace wysiwyf::display
