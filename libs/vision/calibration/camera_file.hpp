#pragma once
// A camera's calibration file as the pipelines read it (config/calibration/*.yaml, OpenCV
// FileStorage): image_width, image_height, camera_matrix, distortion_coefficients (the camera
// component, stereo_depth, camera_sim) and, for camera-fixed mode, base_T_eye (camera_fixed: where
// the camera stands in the robot's base frame); for a camera of a rectified stereo pair also
// rectification_matrix and projection_matrix.
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "calibration/camera_model.hpp"

namespace wysiwyf::vision::calibration {

struct CameraFile {
  CameraIntrinsics intrinsics;
  std::optional<Eigen::Isometry3d> base_T_eye;
  // A camera of a rectified stereo pair (wysiwyf calibrate stereo): its rectifying rotation and
  // rectified projection (the camera component's rectification_matrix, projection_matrix).
  std::optional<cv::Matx33d> rectification;
  std::optional<cv::Matx34d> projection;
};

// Reads and checks the file: a 3x3 camera_matrix with positive focal lengths and its principal
// point inside the image, 4, 5, 8, 12 or 14 finite distortion coefficients (the first five kept),
// an image size of 1..16384 px, a rigid base_T_eye if present. Throws std::runtime_error naming
// the file, the key and what was expected.
CameraFile load_camera_file(const std::string& path);

// Writes the file (FileStorage YAML) with `comment` (one or more lines) at its top; base_T_eye
// only when present. Throws std::runtime_error when the file cannot be written.
void save_camera_file(const std::string& path, const CameraFile& file, const std::string& comment);

}  // namespace wysiwyf::vision::calibration
