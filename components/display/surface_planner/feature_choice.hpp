#pragma once
// Which feature the hand is about to touch (paper section 2.3: "the device is placed at the
// position of the virtual object closest from the user"): the hand's motion extrapolated over a
// horizon, cut where it would enter an object or meet a knob, and the displayable feature
// nearest that path.
// With hysteresis, so the target does not flip between two faces the path passes equally near:
// another feature takes over only when it is nearer by `hysteresis` for `dwell`. A feature the
// arm cannot display counts `unreachable_penalty` farther: where the path is as near to one the
// arm can reach (a hand at rest between two faces), the plate goes there; a path going straight
// for the unreachable one still chooses it (and the planner says it cannot).
// A feature is touched from its face's outside, and a path beyond the edge between two faces, as
// near both by distance, is nearer to the one whose plane it is farther out of: the distance
// grows by how far the path is past the edge's bisector.
#include <cstdint>
#include <set>
#include <vector>

#include <Eigen/Geometry>

#include "scene/scene.hpp"

namespace wysiwyf::display {

class FeatureChooser {
 public:
  FeatureChooser(double horizon_s, double hysteresis_m, double dwell_s, double unreachable_penalty_m = 0)
      : horizon_(horizon_s),
        hysteresis_(hysteresis_m),
        penalty_(unreachable_penalty_m),
        dwell_ns_(static_cast<std::int64_t>(dwell_s * 1e9)) {}

  // The feature for a hand at `position` moving at `velocity` (base frame), the objects at
  // base_T_obj (by body index); null when the scene has none. unreachable: the features the arm
  // cannot display where their objects are now (null: none).
  const haptics::DisplayFeature* choose(const haptics::Scene& scene, const std::vector<Eigen::Isometry3d>& base_T_obj,
                                        const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                                        std::int64_t now_ns,
                                        const std::set<const haptics::DisplayFeature*>* unreachable = nullptr);
  const haptics::DisplayFeature* current() const { return current_; }
  // The distance from the predicted path to the current feature, m.
  double distance() const { return current_distance_; }
  void reset() { current_ = nullptr, challenger_ = nullptr; }

 private:
  double horizon_, hysteresis_, penalty_;
  std::int64_t dwell_ns_;
  const haptics::DisplayFeature* current_ = nullptr;
  double current_distance_ = 0;
  const haptics::DisplayFeature* challenger_ = nullptr;
  std::int64_t challenger_since_ns_ = 0;
  std::vector<Eigen::Vector3d> path_;
};

}  // namespace wysiwyf::display
