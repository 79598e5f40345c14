#include "feature_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wysiwyf::display {

namespace {

// Where along p + t d, t in [0, t_max], the ray first enters a box (its frame, half extents);
// t_max if it does not (Kay and Kajiya's slabs).
double box_entry(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const Eigen::Vector3d& half, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(p[i]) >= half[i]) return t_max;
      continue;
    }
    const double a = (-half[i] - p[i]) / d[i], b = (half[i] - p[i]) / d[i];
    t0 = std::max(t0, std::min(a, b)), t1 = std::min(t1, std::max(a, b));
  }
  return t0 <= t1 ? t0 : t_max;
}

// Where it first comes within `radius` of `centre`; t_max if it does not.
double sphere_entry(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const Eigen::Vector3d& centre, double radius,
                    double t_max) {
  const Eigen::Vector3d m = p - centre;
  const double a = d.squaredNorm(), b = m.dot(d), c = m.squaredNorm() - radius * radius;
  if (c <= 0) return 0.0;  // there already
  const double disc = b * b - a * c;
  if (a < 1e-18 || disc < 0) return t_max;
  const double t = (-b - std::sqrt(disc)) / a;
  return t >= 0 && t < t_max ? t : t_max;
}

}  // namespace

const haptics::DisplayFeature* FeatureChooser::choose(const haptics::Scene& scene,
                                                      const std::vector<Eigen::Isometry3d>& base_T_obj,
                                                      const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                                                      std::int64_t now_ns,
                                                      const std::set<const haptics::DisplayFeature*>* unreachable) {
  // The predicted path: up to the horizon, or to where the hand would stop: entering an object,
  // or on a knob's tip (within its radius).
  double t_end = horizon_;
  for (std::size_t i = 0; i < scene.models.size(); ++i) {
    const Eigen::Isometry3d obj_T_base = base_T_obj[i].inverse();
    t_end = std::min(t_end, box_entry(obj_T_base * position, obj_T_base.linear() * velocity,
                                      scene.models[i].half_extents, horizon_));
  }
  for (const auto& f : scene.features)
    if (f.kind == haptics::DisplayFeature::Kind::kKnob)
      t_end = std::min(t_end, sphere_entry(position, velocity, base_T_obj[static_cast<std::size_t>(f.body)] * f.touch,
                                           f.knob_radius, horizon_));
  constexpr int kSamples = 96;
  path_.clear();
  for (int k = 0; k <= kSamples; ++k) path_.push_back(position + velocity * (t_end * k / kSamples));
  auto distance_to = [&](const haptics::DisplayFeature& f) {
    const Eigen::Isometry3d obj_T_base = base_T_obj[static_cast<std::size_t>(f.body)].inverse();
    const Eigen::Vector3d& half = scene.models[static_cast<std::size_t>(f.body)].half_extents;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& p : path_) {
      const Eigen::Vector3d local = obj_T_base * p;
      if (f.in_front(local)) best = std::min(best, f.distance(local) + f.past_edges(local, half));
    }
    return unreachable && unreachable->count(&f) ? best + penalty_ : best;
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
