#include "rigid_body/integration_groups.hpp"

#include <utility>

namespace wysiwyf::haptics {

void IntegrationGroups::form(const WorldModel& model, const WorldState& state, const MakeIntegrator& make) {
  const std::size_t n = model.bodies.size();
  bodies_.reset(n);
  const auto join = [&](const ContactFeature& f) {
    if (joins_dynamic_bodies(f, model.slot)) bodies_.join(f.a, f.b);
  };
  for (const ActiveContact& c : state.resting) join(c.feature);
  for (const ContactFeature& f : state.watched) join(f);
  // Groups that watch nothing cannot hit anything within the step: they are integrated together,
  // as one (a grid of resting cubes: one integrator, not one per cube, whose restart and step
  // cost as much as the whole cube's physics).
  eventful_.assign(n, 0);
  for (const ContactFeature& f : state.watched)
    eventful_[static_cast<std::size_t>(bodies_.root(dynamic_body(f, model.slot)))] = 1;
  int calm = -1;
  for (const int i : model.dynamic) {
    const int r = bodies_.root(i);
    if (eventful_[static_cast<std::size_t>(r)]) continue;
    if (calm < 0) calm = r;
    bodies_.join(r, calm);
  }
  for (std::size_t k = 0; k < size_; ++k) {  // (the integrators go back, by size, to be handed out again)
    IntegrationGroup& g = groups_[k];
    if (g.integrator) spare_[g.bodies.size()].push_back(std::move(g.integrator));
  }
  size_ = 0;
  group_.assign(n, -1);
  place_.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {  // (ascending: each group's bodies in order)
    if (model.slot[i] < 0) continue;
    int& g = group_[static_cast<std::size_t>(bodies_.root(static_cast<int>(i)))];
    if (g < 0) {
      g = static_cast<int>(size_++);
      if (groups_.size() < size_) groups_.emplace_back();
      groups_[size_ - 1].bodies.clear();
    }
    group_[i] = g;
    std::vector<int>& bodies = groups_[static_cast<std::size_t>(g)].bodies;
    place_[i] = static_cast<int>(bodies.size());
    bodies.push_back(static_cast<int>(i));
  }
  for (std::size_t k = 0; k < size_; ++k) {
    IntegrationGroup& g = groups_[k];
    const std::size_t count = g.bodies.size();
    if (spare_.size() <= count) spare_.resize(count + 1);
    if (spare_[count].empty()) {
      g.integrator = make(static_cast<int>(count));
    } else {
      g.integrator = std::move(spare_[count].back());
      spare_[count].pop_back();
    }
  }
}

int IntegrationGroups::group_of(const ContactFeature& f, const WorldModel& model) const {
  return group_[static_cast<std::size_t>(dynamic_body(f, model.slot))];
}

void IntegrationGroups::assign(const WorldModel& model, const WorldState& state) {
  for (std::size_t k = 0; k < size_; ++k) {
    IntegrationGroup& g = groups_[k];
    g.islands.clear();
    g.watched.clear();
    g.awake = false;
    for (const int i : g.bodies) g.awake = g.awake || !state.asleep[static_cast<std::size_t>(i)];
  }
  asleep_islands_.clear();
  asleep_watched_.clear();
  for (std::size_t k = 0; k < state.islands.size(); ++k) {
    IntegrationGroup& g =
        groups_[static_cast<std::size_t>(group_of(state.resting[state.islands[k].begin].feature, model))];
    (g.awake ? g.islands : asleep_islands_).push_back(k);
  }
  for (std::size_t k = 0; k < state.watched.size(); ++k) {
    IntegrationGroup& g = groups_[static_cast<std::size_t>(group_of(state.watched[k], model))];
    (g.awake ? g.watched : asleep_watched_).push_back(k);
  }
}

}  // namespace wysiwyf::haptics
