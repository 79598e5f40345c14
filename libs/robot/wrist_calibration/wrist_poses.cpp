#include "wrist_calibration/wrist_poses.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wysiwyf::robot {

Eigen::Vector3d gravity_in_frame(const ArmModel& arm, const JointRef& q, FrameId f,
                                 const Eigen::Vector3d& gravity_base) {
  return arm.fk(q, f).linear().transpose() * gravity_base;
}

std::vector<JointVector> wrist_calibration_poses(const ArmModel& arm, const JointRef& q_home, FrameId f, int count,
                                                 const Eigen::Vector3d& gravity_base) {
  const int n = arm.dof();
  if (q_home.size() != n)
    throw std::invalid_argument("wrist poses: " + std::to_string(q_home.size()) + " home joints; expected " +
                                std::to_string(n));
  if (!arm.limits().within(q_home)) throw std::invalid_argument("wrist poses: the home joints lie outside the limits");
  if (count < 1) throw std::invalid_argument("wrist poses: expected a count of at least 1");
  // A grid over each of the last three joints (within its limits, one turn at most).
  constexpr int kSteps = 9;
  const int first = std::max(0, n - 3);
  std::vector<JointVector> candidates{JointVector(q_home)};
  for (int j = first; j < n; ++j) {
    const double lo = std::max(arm.limits().lower[j], -M_PI), hi = std::min(arm.limits().upper[j], M_PI);
    std::vector<JointVector> next;
    for (const JointVector& c : candidates)
      for (int k = 0; k < kSteps; ++k) {
        JointVector q = c;
        q[j] = lo + (hi - lo) * k / (kSteps - 1);
        next.push_back(q);
      }
    candidates.swap(next);
  }
  std::vector<Eigen::Vector3d> dirs;
  for (const JointVector& q : candidates) dirs.push_back(gravity_in_frame(arm, q, f, gravity_base).normalized());
  // Start at home, then add whichever candidate is farthest from every chosen direction.
  std::vector<JointVector> chosen{JointVector(q_home)};
  std::vector<double> nearest(candidates.size(), INFINITY);
  Eigen::Vector3d last = gravity_in_frame(arm, q_home, f, gravity_base).normalized();
  while (static_cast<int>(chosen.size()) < count) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      nearest[i] = std::min(nearest[i], std::acos(std::clamp(dirs[i].dot(last), -1.0, 1.0)));
      if (nearest[i] > nearest[best]) best = i;
    }
    chosen.push_back(candidates[best]);
    last = dirs[best];
  }
  return chosen;
}

}  // namespace wysiwyf::robot
