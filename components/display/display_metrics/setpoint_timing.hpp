#pragma once
// The arm's timing, from its setpoints: setpoint to motion (FollowingLag: how long after a moving
// setpoint was made the plate gets there) and sensor sample to setpoint (SensorToSetpoint: how
// long after a wrench or hand sample the setpoint answering it was made).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "following_lag.hpp"
#include "sensor_to_setpoint.hpp"

namespace wysiwyf::display {

class SetpointTiming {
 public:
  // lag_min_speed: m/s, setpoints commanding motion at least this fast are timed to the plate.
  explicit SetpointTiming(double lag_min_speed = 0.02) : lag_(lag_min_speed, kGiveUpNs) {}

  // A setpoint from `source` stamped t, answering the sensor sample stamped sensed_ns (0: none).
  // Give the setpoints before the plate poses after them; they are timed against the sensor
  // samples at answer_setpoints().
  void add_setpoint(const std::string& source, std::int64_t t, const Eigen::Vector3d& position,
                    const Eigen::Vector3d& velocity, std::int64_t sensed_ns);
  void add_plate(std::int64_t t, const Eigen::Vector3d& position) { lag_.plate(t, position); }
  // A sample of `sensor` ("wrench", "hand") stamped t.
  void add_sensor_sample(const std::string& sensor, std::int64_t t) { sensed_.sample(sensor, t); }
  // Times the setpoints given since the last call against the sensor samples given so far.
  void answer_setpoints();

  // The run's figures, for the log.
  std::vector<std::string> end_lines() const;
  // The summary's "setpoint_to_motion" and "sensor_to_setpoint" members.
  void write_json(std::ostream& j) const;

 private:
  static constexpr std::int64_t kGiveUpNs = 500'000'000;  // a moving setpoint not reached by then: not reached
  struct Setpoint {
    std::string source;
    std::int64_t stamp, sensed;
  };
  FollowingLag lag_;
  SensorToSetpoint sensed_;
  std::vector<Setpoint> unanswered_;
};

}  // namespace wysiwyf::display
