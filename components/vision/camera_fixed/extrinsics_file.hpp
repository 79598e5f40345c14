#pragma once
// A camera's calibrated pose from an OpenCV FileStorage file (YAML, XML or JSON), in any of the
// forms calibration tools write:
//   rvec, tvec       (cv::solvePnP, cv::calibrateCamera: X_eye = R(rvec) X_base + tvec, m)
//   eye_T_base       (a 4x4 matrix: base coordinates to eye coordinates)
//   base_T_eye       (a 4x4 matrix: where the camera is in the base frame)
#include <string>

#include <Eigen/Geometry>

namespace wysiwyf::vision {

// eye_T_base from the file; throws std::invalid_argument naming the file and what was expected.
Eigen::Isometry3d load_eye_T_base(const std::string& path);

}  // namespace wysiwyf::vision
