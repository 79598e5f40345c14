#include "following_lag.hpp"

namespace wysiwyf::display {

void FollowingLag::setpoint(std::int64_t t, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity) {
  const double speed = velocity.norm();
  if (!(speed > min_speed_)) return;  // holding still (or not finite): nothing to reach
  pending_.push_back({t, position, velocity / speed});
}

void FollowingLag::plate(std::int64_t t, const Eigen::Vector3d& position) {
  while (!pending_.empty()) {
    const Pending& s = pending_.front();
    if (s.t > t) return;  // made after this pose
    if ((position - s.position).dot(s.direction) >= 0) {
      lag_ms_.add(static_cast<double>(t - s.t) * 1e-6, s.t);
    } else if (t - s.t <= give_up_ns_) {
      return;  // not there yet; later setpoints are further along
    } else {
      ++not_reached_;
    }
    pending_.pop_front();
  }
}

}  // namespace wysiwyf::display
