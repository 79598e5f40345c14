#pragma once
// Registration errors and their statistics. Haptic: the real plate against where the attachment
// holds it on the moving virtual object (base_T_obj * obj_T_dev). Visual: where the virtual
// object's points are drawn (the tracked camera pose) against where they should be (the true
// one), in mm in the camera frame and in pixels.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "stats/percentiles.hpp"

namespace wysiwyf::display {

struct RegistrationError {
  double mm = 0;   // plate origin from where it should be
  double deg = 0;  // plate orientation from it
};

RegistrationError registration_error(const Eigen::Isometry3d& want, const Eigen::Isometry3d& plate);

struct VisualError {
  double mm = 0;  // the largest offset of a point as drawn from where it should be, camera frame
  double px = 0;  // the largest offset of its image
};

// Over `base_points`, drawn through tracked_eye_T_base instead of true_eye_T_base, seen by a
// pinhole camera K = (fx, fy, cx, cy). Points behind the camera are skipped.
VisualError visual_error(const Eigen::Isometry3d& tracked_eye_T_base, const Eigen::Isometry3d& true_eye_T_base,
                         const std::vector<Eigen::Vector3d>& base_points, const std::array<double, 4>& K);

using stats::Percentiles;

struct RegistrationStats {
  Percentiles mm, deg;
  void add(RegistrationError e, std::int64_t t_ns) { mm.add(e.mm, t_ns), deg.add(e.deg, t_ns); }
};

}  // namespace wysiwyf::display
