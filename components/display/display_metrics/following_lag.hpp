#pragma once
// Setpoint to motion: how long after a setpoint was made the plate gets there. For each
// setpoint commanding motion (its twist faster than `min_speed`), the lag is the time from its
// stamp to the first plate pose that has reached it along the commanded direction; a setpoint
// the plate has not reached within `give_up` is counted as not reached (stopped short, or the
// command changed course).
#include <cstdint>
#include <deque>

#include <Eigen/Core>

#include "stats/percentiles.hpp"

namespace wysiwyf::display {

class FollowingLag {
 public:
  FollowingLag(double min_speed, std::int64_t give_up_ns) : min_speed_(min_speed), give_up_ns_(give_up_ns) {}

  void setpoint(std::int64_t t, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity);
  void plate(std::int64_t t, const Eigen::Vector3d& position);

  const stats::Percentiles& lag_ms() const { return lag_ms_; }
  std::size_t not_reached() const { return not_reached_; }

 private:
  struct Pending {
    std::int64_t t;
    Eigen::Vector3d position, direction;
  };
  double min_speed_;
  std::int64_t give_up_ns_;
  std::deque<Pending> pending_;
  stats::Percentiles lag_ms_;
  std::size_t not_reached_ = 0;
};

}  // namespace wysiwyf::display
