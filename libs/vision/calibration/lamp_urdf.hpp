#pragma once
// The plate's lamp positions written into a copy of the arm's URDF, where the marker tracker and
// the camera simulation read them: each lamp link's fixed joint gets the fitted origin (in the
// joint's parent link), everything else of the file stays as it was, and a comment at the top
// says where the positions came from.
#include <map>
#include <string>

#include <Eigen/Core>

namespace wysiwyf::vision::calibration {

// The parent link of the joint whose child is `child_link` in the URDF `urdf_path`. Throws
// std::runtime_error naming the file when it cannot be read or has no such joint.
std::string joint_parent(const std::string& urdf_path, const std::string& child_link);

// Writes `urdf_in` to `urdf_out` with the origin xyz of the joint of each child link of
// `parent_p_child` (m, in that joint's parent link) replaced; the rotation is kept. `note` goes in
// a comment before the robot element. Throws std::runtime_error naming the file and the link.
void write_lamps_urdf(const std::string& urdf_in, const std::string& urdf_out,
                      const std::map<std::string, Eigen::Vector3d>& parent_p_child, const std::string& note);

}  // namespace wysiwyf::vision::calibration
