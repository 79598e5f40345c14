#pragma once
// The way a hand reaches a point on a box's face: in along the face's normal, and around the box
// rather than through it (people do not reach through what they see). A quadratic Bezier from
// where the hand is, through a control point out along the normal from the target, to the target:
// its last stretch is square to the face. Straight when the hand is already in front of it.
#include <Eigen/Geometry>

namespace wysiwyf::display {

struct ReachPath {
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  double lead = 0;  // m: the control point this far out along the normal from the target

  // The point at progress s in [0, 1] toward `to` (which may move: the face moves with its body).
  Eigen::Vector3d at(double s, const Eigen::Vector3d& to, const Eigen::Vector3d& normal) const;
  // The path's length toward `to`.
  double length(const Eigen::Vector3d& to, const Eigen::Vector3d& normal) const;
};

// The path from `from` to `to` on the face with outward `normal` of a box (base_T_box, half
// extents) that keeps `clearance` m from the box, the lead as short as does that (at most 0.5 m).
ReachPath reach_around(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& normal,
                       const Eigen::Isometry3d& base_T_box, const Eigen::Vector3d& half, double clearance);

}  // namespace wysiwyf::display
