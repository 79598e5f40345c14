#pragma once
// The truth the calibration tests measure against: the shipped simulated camera
// (config/calibration/sim_camera.yaml) perturbed by a seeded error, as a real camera of that model
// would differ from its data sheet.
#include <random>
#include <string>

#include "calibration/camera_file.hpp"

namespace wysiwyf::test {

inline vision::calibration::CameraIntrinsics perturbed_sim_camera(unsigned seed) {
  auto cam = vision::calibration::load_camera_file(std::string(WYSIWYF_CONFIG_DIR) + "/calibration/sim_camera.yaml")
                 .intrinsics;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  cam.camera_matrix(0, 0) *= 1 + 0.03 * u(rng);
  cam.camera_matrix(1, 1) = cam.camera_matrix(0, 0) * (1 + 0.003 * u(rng));
  cam.camera_matrix(0, 2) += 8 * u(rng);
  cam.camera_matrix(1, 2) += 8 * u(rng);
  cam.distortion = {-0.08 + 0.1 * u(rng), 0.05 * u(rng), 0.001 * u(rng), 0.001 * u(rng), 0};
  return cam;
}

}  // namespace wysiwyf::test
