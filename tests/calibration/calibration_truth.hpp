#pragma once
// The truth the calibration tests measure against: the shipped simulated camera
// (config/calibration/sim_camera.yaml) perturbed by a seeded error, as a real camera of that model
// would differ from its data sheet.
#include <string>

#include "calibration/board_view_sim.hpp"
#include "calibration/camera_file.hpp"

namespace wysiwyf::test {

inline vision::calibration::CameraIntrinsics perturbed_sim_camera(unsigned seed) {
  return vision::calibration::perturbed_camera(
      vision::calibration::load_camera_file(std::string(WYSIWYF_CONFIG_DIR) + "/calibration/sim_camera.yaml")
          .intrinsics,
      seed);
}

}  // namespace wysiwyf::test
