#pragma once
// The robot-world calibration's input as a file (YAML): at each pose, the arm's joints and the
// camera's image of the board on the plate, a path relative to the file's folder:
//   views:
//     - {image: pose_01.png, joints: [q1, ..., qn]}
#include <string>
#include <vector>

#include <Eigen/Core>

namespace wysiwyf::vision::calibration {

struct FlangeViewEntry {
  std::string image;  // the path as resolved (the file's folder + the entry's path)
  std::string label;  // the entry's path as written
  Eigen::VectorXd joints;
};

// Throws std::runtime_error "file:line:col: what; expected ..." for an unreadable file, a wrong key,
// type or joint count, a non-finite number, an empty or over-long path, more than 1000 views.
std::vector<FlangeViewEntry> load_flange_views(const std::string& path, int joints);

}  // namespace wysiwyf::vision::calibration
