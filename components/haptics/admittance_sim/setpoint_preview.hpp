#pragma once
// The setpoint sent ahead of the held object's impacts. The object stops within a millisecond
// when it meets a wall; an arm commanded to stop that abruptly runs past it (its servo and
// trajectory tracker cannot stop at once) and the plate overshoots the object's face by the
// braking distance. The setpoint is instead the object's device pose averaged over a window
// centred on now: the past half from the poses the object had, the future half from a look-ahead
// of the world (the same physics, the user's wrench held). Averaging a path that stops makes a
// setpoint that starts braking half a window before the impact, decelerates at (speed change) /
// window and arrives where the object stopped, never beyond it; the largest difference from the
// object's pose is (speed change) x window / 8 (0.24 mm for 9.4 cm/s in 20 ms). Along a straight
// path at constant speed the average is the pose itself, and under an acceleration a it is ahead
// by a window^2 / 24 (17 um for 1 m/s^2 in 20 ms). Its twist is the average's derivative:
// (pose at +half - pose at -half) / window.
#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

namespace wysiwyf::haptics {

struct PreviewedSetpoint {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // m/s, the pose's origin (base frame)
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // rad/s (base frame)
};

class SetpointPreview {
 public:
  // half_samples: the window's half in samples of the tick period dt (0: the pose as it is).
  SetpointPreview(std::size_t half_samples, double dt);

  // The look-ahead's length: how many ticks ahead future() must hold.
  std::size_t half_samples() const { return half_; }
  // Forgets the past: every past sample is `pose` (the object at rest there; at an attachment).
  void restart(const Eigen::Isometry3d& pose);
  // The pose now, one tick after the last one recorded.
  void record(const Eigen::Isometry3d& pose);
  // The poses predicted for the next half_samples() ticks (future[k]: k + 1 ticks ahead).
  std::vector<Eigen::Isometry3d>& future() { return future_; }
  // The window's average and its twist, from the recorded past, the last recorded pose as now and
  // future().
  PreviewedSetpoint setpoint() const;

 private:
  const Eigen::Isometry3d& sample(long k) const;  // k ticks from now, -half_ .. half_

  std::size_t half_;
  double dt_;
  std::vector<Eigen::Isometry3d> past_;  // a ring of half_ + 1 samples: now and half_ before it
  std::size_t newest_ = 0;               // past_[newest_] is now
  std::vector<Eigen::Isometry3d> future_;
};

}  // namespace wysiwyf::haptics
