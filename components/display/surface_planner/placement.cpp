#include "placement.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::display {

std::vector<Eigen::Isometry3d> plate_poses(const haptics::DisplayFeature& feature, const Eigen::Isometry3d& base_T_obj,
                                           const Eigen::Isometry3d& base_T_now) {
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k < 4; ++k)
    poses.push_back(base_T_obj * feature.obj_T_plate * Eigen::AngleAxisd(k * M_PI / 2, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond now(base_T_now.linear());
  std::stable_sort(poses.begin(), poses.end(), [&](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return Eigen::Quaterniond(a.linear()).angularDistance(now) < Eigen::Quaterniond(b.linear()).angularDistance(now);
  });
  return poses;
}

std::string path_reachable(const robot::ArmModel& model, PlatePath path, const robot::JointRef& q_now,
                           robot::JointVector& q_end, double step, double max_joint_step) {
  robot::JointVector q = q_now;
  while (true) {
    const robot::ArmIkResult ik = model.ik_nearest(path.pose(), q);
    if (!ik.ok())
      return std::string("the arm cannot take the plate pose ") + std::to_string(path.remaining_time()) +
             " s before the target: " + robot::to_string(ik.status);
    if ((ik.q - q).cwiseAbs().maxCoeff() > max_joint_step)
      return "the way there changes the arm's posture (a joint turns " +
             std::to_string((ik.q - q).cwiseAbs().maxCoeff()) + " rad in " + std::to_string(step) + " s)";
    q = ik.q;
    if (path.done()) break;
    path.advance(step, 1.0);
  }
  q_end = q;
  return {};
}

}  // namespace wysiwyf::display
