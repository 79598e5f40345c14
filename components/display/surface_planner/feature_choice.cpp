#include "feature_choice.hpp"

#include <limits>

namespace wysiwyf::display {

namespace {

bool inside(const haptics::Scene& scene, const std::vector<Eigen::Isometry3d>& base_T_obj, const Eigen::Vector3d& p) {
  for (std::size_t i = 0; i < scene.models.size(); ++i) {
    const Eigen::Vector3d local = base_T_obj[i].inverse() * p;
    if ((local.cwiseAbs().array() < scene.models[i].half_extents.array()).all()) return true;
  }
  return false;
}

}  // namespace

const haptics::DisplayFeature* FeatureChooser::choose(const haptics::Scene& scene,
                                                      const std::vector<Eigen::Isometry3d>& base_T_obj,
                                                      const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                                                      std::int64_t now_ns) {
  // The predicted path: up to the horizon, or until it would enter an object (the hand stops there).
  constexpr int kSamples = 24;
  path_.clear();
  for (int k = 0; k <= kSamples; ++k) {
    const Eigen::Vector3d p = position + velocity * (horizon_ * k / kSamples);
    if (k > 0 && inside(scene, base_T_obj, p)) break;
    path_.push_back(p);
  }
  auto distance_to = [&](const haptics::DisplayFeature& f) {
    const Eigen::Isometry3d obj_T_base = base_T_obj[static_cast<std::size_t>(f.body)].inverse();
    double best = std::numeric_limits<double>::infinity();
    for (const auto& p : path_) {
      const Eigen::Vector3d local = obj_T_base * p;
      if (f.in_front(local)) best = std::min(best, f.distance(local));  // (a face is touched from its outside)
    }
    return best;
  };
  const haptics::DisplayFeature* nearest = nullptr;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (const auto& f : scene.features) {
    const double d = distance_to(f);
    if (d < nearest_distance) nearest = &f, nearest_distance = d;
  }
  if (!nearest) return current_;
  if (!current_) {
    current_ = nearest, current_distance_ = nearest_distance;
    return current_;
  }
  current_distance_ = distance_to(*current_);
  if (nearest == current_ || nearest_distance > current_distance_ - hysteresis_) {
    challenger_ = nullptr;
    return current_;
  }
  if (nearest != challenger_) challenger_ = nearest, challenger_since_ns_ = now_ns;
  if (now_ns - challenger_since_ns_ >= dwell_ns_) {
    current_ = nearest, current_distance_ = nearest_distance;
    challenger_ = nullptr;
  }
  return current_;
}

}  // namespace wysiwyf::display
