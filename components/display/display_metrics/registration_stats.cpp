#include "registration_stats.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::display {

RegistrationError registration_error(const Eigen::Isometry3d& want, const Eigen::Isometry3d& plate) {
  return {(want.translation() - plate.translation()).norm() * 1e3,
          Eigen::Quaterniond(want.linear()).angularDistance(Eigen::Quaterniond(plate.linear())) * 180 / M_PI};
}

VisualError visual_error(const Eigen::Isometry3d& tracked_eye_T_base, const Eigen::Isometry3d& true_eye_T_base,
                         const std::vector<Eigen::Vector3d>& base_points, const std::array<double, 4>& K) {
  VisualError e;
  for (const Eigen::Vector3d& p : base_points) {
    const Eigen::Vector3d drawn = tracked_eye_T_base * p, truth = true_eye_T_base * p;
    if (drawn.z() <= 0 || truth.z() <= 0) continue;
    e.mm = std::max(e.mm, (drawn - truth).norm() * 1e3);
    const Eigen::Vector2d a(K[0] * drawn.x() / drawn.z() + K[2], K[1] * drawn.y() / drawn.z() + K[3]);
    const Eigen::Vector2d b(K[0] * truth.x() / truth.z() + K[2], K[1] * truth.y() / truth.z() + K[3]);
    e.px = std::max(e.px, (a - b).norm());
  }
  return e;
}

}  // namespace wysiwyf::display
