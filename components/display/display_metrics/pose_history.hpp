#pragma once
// The truth the measurements are taken against: the plate's poses (base_T_dev) and each virtual
// object's (base_T_obj), by stamp, kept for `history` seconds so that events arriving late still
// find the poses of their moment.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include <Eigen/Geometry>

namespace wysiwyf::display {

struct PoseSample {
  std::int64_t t = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

using PoseTrack = std::deque<PoseSample>;

// The newest sample at or before t (the oldest if none is; nullptr when the track is empty).
const PoseSample* pose_at(const PoseTrack& track, std::int64_t t);

class PoseHistory {
 public:
  explicit PoseHistory(std::int64_t history_ns = 0) : history_ns_(history_ns) {}

  // One track per body of the scene (called once the scene is known).
  void resize_objects(std::size_t bodies) { objects_.resize(bodies); }
  void add_plate(std::int64_t t, const Eigen::Isometry3d& base_T_dev) { plate_.push_back({t, base_T_dev}); }
  void add_object(std::size_t body, std::int64_t t, const Eigen::Isometry3d& base_T_obj) {
    objects_[body].push_back({t, base_T_obj});
  }
  // Drops what is older than `history` before now; each object keeps its last pose before that
  // (an object at rest publishes rarely, and its pose still holds).
  void forget_before(std::int64_t now_ns);

  std::int64_t history_ns() const { return history_ns_; }
  const PoseTrack& plate() const { return plate_; }
  const PoseTrack& object(std::size_t body) const { return objects_[body]; }
  std::size_t bodies() const { return objects_.size(); }

 private:
  std::int64_t history_ns_;
  PoseTrack plate_;
  std::vector<PoseTrack> objects_;
};

}  // namespace wysiwyf::display
