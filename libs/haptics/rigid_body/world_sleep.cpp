// World's sleeping islands (world.hpp, WorldParams::sleep_after): an island whose bodies have all
// been still long enough is left out of the integration until something wakes it.
#include <algorithm>
#include <vector>

#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

bool World::settle_islands(bool may_sleep) {
  const WorldParams& p = model_.params;
  if (p.sleep_after <= 0) return false;
  const double t = state_.t;
  const std::vector<int>& dynamic = *integrated_;  // (within a group's integration, its bodies only)
  for (const int i : dynamic) {  // who moves now: the fastest point of each body, and the user's wrenches
    const bool pushed = !state_.ext_force[i].isZero() || !state_.ext_torque[i].isZero();
    if (pushed) {
      state_.still_since[i] = t;
      continue;
    }
    if (state_.asleep[i] && state_.bodies[i].P.isZero(0) && state_.bodies[i].L.isZero(0)) continue;  // (not hit)
    const BodyKinematics k(model_.bodies[i], state_.bodies[i], model_.inv_inertia_body[i]);
    if (k.v.norm() + k.omega.norm() * model_.bodies[i].half_extents.norm() > p.sleep_speed) state_.still_since[i] = t;
  }
  bool changed = false;
  std::vector<char>& in_island = work_.sleep.in_island;
  in_island.assign(model_.bodies.size(), 0);
  std::vector<int>& bodies = work_.sleep.island_bodies;
  for (ContactIsland& island : state_.islands) {
    bodies.clear();
    for (std::size_t c = island.begin; c < island.end; ++c)
      for (const int i : {state_.resting[c].feature.a, state_.resting[c].feature.b})
        if (model_.slot[i] >= 0 && !in_island[i]) in_island[i] = 1, bodies.push_back(i);
    bool all_asleep = true, still = true;
    for (const int i : bodies) {
      all_asleep = all_asleep && state_.asleep[i];
      still = still && t - state_.still_since[i] >= p.sleep_after - 1e-12;
    }
    island.asleep = still && (may_sleep || all_asleep);
    for (const int i : bodies) {
      if (island.asleep == (state_.asleep[i] != 0)) continue;
      changed = true;
      state_.asleep[i] = island.asleep;
      if (island.asleep) {
        state_.bodies[i].P.setZero(), state_.bodies[i].L.setZero();
        state_.static_poses[i] = model_.pose_of(i, state_.bodies[i]);  // (where it stays)
      } else {
        state_.still_since[i] = t;
      }
    }
  }
  for (const int i : dynamic)  // (a body touching nothing falls or floats: awake)
    if (!in_island[i] && state_.asleep[i]) state_.asleep[i] = 0, state_.still_since[i] = t, changed = true;
  return changed;
}

bool World::all_asleep() const {
  return std::all_of(model_.dynamic.begin(), model_.dynamic.end(), [&](int i) { return state_.asleep[i] != 0; });
}

}  // namespace wysiwyf::haptics
