#pragma once
// Visual registration: for every image, the dynamic bodies' corners drawn through the camera pose
// the display drew from (the tracker's eye_T_base) against the true one (the simulator's): the
// largest offset in mm (camera frame) and in pixels, p50/p99/max over the run. A tracked pose is
// measured against the true pose of the same image (equal stamps).
#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "pose_history.hpp"
#include "registration_stats.hpp"
#include "scene/scene.hpp"

namespace wysiwyf::display {

class VisualRegistration {
 public:
  // The camera's intrinsics (fx, fy, cx, cy; pixels). Without them nothing is measured.
  void set_intrinsics(const std::array<double, 4>& K) { K_ = K; }
  void add_true_pose(std::int64_t t, const Eigen::Isometry3d& eye_T_base) { true_poses_.push_back({t, eye_T_base}); }
  void add_tracked_pose(std::int64_t t, const Eigen::Isometry3d& eye_T_base) { tracked_.push_back({t, eye_T_base}); }
  // Measures every tracked pose whose true pose has come; keeps those whose truth may still come.
  void measure(const haptics::Scene& scene, const PoseHistory& poses);

  // The latest image's offset, mm (for the time series).
  const std::optional<double>& latest_mm() const { return last_mm_; }
  // The run's figures, for the log; empty without any image.
  std::string end_line() const;
  // The summary's "visual_registration" member.
  void write_json(std::ostream& j) const;

 private:
  static constexpr std::size_t kKept = 64;  // poses waiting for their match
  std::array<double, 4> K_{};
  PoseTrack tracked_, true_poses_;
  std::vector<Eigen::Vector3d> corners_;  // this image's corners, base frame
  Percentiles mm_, px_;
  std::optional<double> last_mm_;
};

}  // namespace wysiwyf::display
