#include "reach_path.hpp"

#include <algorithm>

namespace wysiwyf::display {

namespace {

// How far a point is outside a box (0 inside), box frame.
double outside(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
  return (p.cwiseAbs() - half).cwiseMax(0.0).norm();
}

}  // namespace

Eigen::Vector3d ReachPath::at(double s, const Eigen::Vector3d& to, const Eigen::Vector3d& normal) const {
  const Eigen::Vector3d control = to + lead * normal;
  return (1 - s) * (1 - s) * from + 2 * s * (1 - s) * control + s * s * to;
}

double ReachPath::length(const Eigen::Vector3d& to, const Eigen::Vector3d& normal) const {
  double length = 0;
  Eigen::Vector3d last = from;
  for (int i = 1; i <= 32; ++i) {
    const Eigen::Vector3d p = at(i / 32.0, to, normal);
    length += (p - last).norm();
    last = p;
  }
  return length;
}

ReachPath reach_around(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& normal,
                       const Eigen::Isometry3d& base_T_box, const Eigen::Vector3d& half, double clearance) {
  const Eigen::Isometry3d box_T_base = base_T_box.inverse();
  ReachPath path{from, std::max(0.0, (from - to).dot(normal))};  // in front already: a straight line
  auto clears = [&] {
    // The last stretch, within `clearance` of the target, comes in to the face: not judged.
    for (int i = 0; i <= 64; ++i) {
      const Eigen::Vector3d p = path.at(i / 64.0, to, normal);
      if ((p - to).norm() > clearance && outside(box_T_base * p, half) < clearance) return false;
    }
    return true;
  };
  if (clears()) return path;
  for (path.lead = 0.05; path.lead < 0.5; path.lead *= 1.25)
    if (clears()) return path;
  return path;
}

}  // namespace wysiwyf::display
