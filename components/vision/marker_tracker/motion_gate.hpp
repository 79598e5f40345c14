#pragma once
// How far the camera can have gone since the tracker last trusted its pose: a head, or a camera
// stand being moved, has a top speed and a top turn rate, so an estimate of eye_T_base that puts
// the camera farther than that from the last trusted one is a wrong fix (blobs given to the wrong
// lamps, the wrong one of IPPE's two solutions for the coplanar lamps), not motion. The bound
// grows with the time since that estimate, plus what that estimate itself may be off by.
#include <Eigen/Geometry>

namespace wysiwyf::vision {

struct MotionLimits {
  double max_speed = 1.0;      // m/s: the camera's centre
  double max_turn_rate = 3.0;  // rad/s: its axes
  // What a trusted estimate may be off by: a fresh fix's few centimetres and hundredths of a
  // radian, whose rotation error moves the camera's centre over the metre to the base.
  double slack_m = 0.05, slack_rad = 0.05;
};

// The camera's motion between two estimates of eye_T_base: how far its centre moved (in the
// base frame) and by what angle it turned.
struct CameraMotion {
  double distance_m = 0, angle_rad = 0;

  static CameraMotion between(const Eigen::Isometry3d& from_eye_T_base, const Eigen::Isometry3d& to_eye_T_base) {
    const Eigen::Isometry3d base_T_from = from_eye_T_base.inverse(), base_T_to = to_eye_T_base.inverse();
    return {(base_T_to.translation() - base_T_from.translation()).norm(),
            Eigen::AngleAxisd(base_T_from.linear().transpose() * base_T_to.linear()).angle()};
  }
  // Whether a camera within `limits` can have moved this much in dt_s seconds.
  bool possible(double dt_s, const MotionLimits& limits) const {
    return distance_m <= limits.max_speed * dt_s + limits.slack_m &&
           angle_rad <= limits.max_turn_rate * dt_s + limits.slack_rad;
  }
};

}  // namespace wysiwyf::vision
