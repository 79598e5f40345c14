#pragma once
// The bodies a World integrates together (world.hpp): those that a resting contact or a watched
// feature joins, directly or through other bodies (a static body joins none: a table under two
// cubes leaves them apart). Each group has an integrator of its own, so an impact restarts, and
// a hard stretch of contact shortens the steps of, only the bodies it concerns (with one
// integrator for all, 16 boxes landing one after another would restart all 16 at every impact).
// Within a haptic step each group is
// integrated from the step's start to its end before the next: no force or impact passes between
// groups within a step, since two bodies that could meet within it are watched, so grouped.
// The groups that watch no feature (nothing of theirs can hit anything within the step) are
// one group: the cost of an integrator's step and restart is paid once for them all. A group
// whose bodies all sleep is not integrated.
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "rigid_body/ode_integrator.hpp"
#include "rigid_body/union_find.hpp"
#include "rigid_body/world_model.hpp"
#include "rigid_body/world_state.hpp"

namespace wysiwyf::haptics {

struct IntegrationGroup {
  std::vector<int> bodies;                    // its dynamic bodies, ascending: its state vector's order
  std::unique_ptr<OdeIntegrator> integrator;  // sized for them
  bool awake = false;                         // a body of it is awake: integrated this step
  // The step's contacts and watched features that are its own: indices into the state's islands
  // and watched features (assign()).
  std::vector<std::size_t> islands, watched;
};

class IntegrationGroups {
 public:
  // An integrator for `bodies` dynamic bodies (13 numbers each).
  using MakeIntegrator = std::function<std::unique_ptr<OdeIntegrator>(int bodies)>;

  // Forms the groups anew from the state's resting contacts and watched features. Their
  // integrators are the last groups' of the same size, or new ones: each must be restarted.
  void form(const WorldModel& model, const WorldState& state, const MakeIntegrator& make);
  // Which of the state's islands and watched features each group owns, and which groups are
  // awake; the ones no awake group owns are listed in asleep_islands and asleep_watched. The
  // groups must have been formed over the same links (the contacts may have changed since only by
  // impacts, which join no groups).
  void assign(const WorldModel& model, const WorldState& state);

  std::vector<IntegrationGroup>& groups() { return groups_; }
  // The number of groups (from the front of groups()).
  std::size_t size() const { return size_; }
  const std::vector<std::size_t>& asleep_islands() const { return asleep_islands_; }
  const std::vector<std::size_t>& asleep_watched() const { return asleep_watched_; }
  // Body -> its place in its group's state vector (-1: static).
  const std::vector<int>& place() const { return place_; }

 private:
  int group_of(const ContactFeature& f, const WorldModel& model) const;

  std::vector<IntegrationGroup> groups_;  // the first size_ are formed; the rest keep spare integrators
  std::size_t size_ = 0;
  UnionFind bodies_;                                                // the groups being formed
  std::vector<char> eventful_;                                      // per root: its group watches a feature
  std::vector<int> group_;                                          // body -> its group (-1: static)
  std::vector<int> place_;                                          // body -> its place in its group
  std::vector<std::vector<std::unique_ptr<OdeIntegrator>>> spare_;  // by body count
  std::vector<std::size_t> asleep_islands_, asleep_watched_;
};

}  // namespace wysiwyf::haptics
