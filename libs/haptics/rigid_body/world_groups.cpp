// World's contacts shared out among its integration groups and gathered back (world.hpp,
// integration_groups.hpp). While a group is integrated the state holds its islands and watched
// features only, so that everything the integration does (right-hand sides, watched gaps,
// impacts, waking) sees that group alone; the world's are kept in the workspace meanwhile.
#include <algorithm>

#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

namespace {

// Island `island` of the contacts `from`, appended to `to` (its range rebased there); the island
// as it is now.
ContactIsland append_island(ContactIsland island, const std::vector<ActiveContact>& from,
                            std::vector<ActiveContact>& to) {
  const auto first = from.begin() + static_cast<std::ptrdiff_t>(island.begin);
  const auto last = from.begin() + static_cast<std::ptrdiff_t>(island.end);
  island.begin = to.size();
  to.insert(to.end(), first, last);
  island.end = to.size();
  return island;
}

}  // namespace

void World::take_share(const IntegrationGroup& g, bool restart) {
  GroupShareWork& share = work_.share;
  state_.resting.clear();
  state_.islands.clear();
  for (const std::size_t k : g.islands)
    state_.islands.push_back(append_island(share.all_islands[k], share.all_resting, state_.resting));
  state_.watched.clear();
  state_.watched_gaps.clear();
  for (const std::size_t k : g.watched) {
    state_.watched.push_back(share.all_watched[k]);
    if (!restart) state_.watched_gaps.push_back(share.all_gaps[k]);  // (restarting: found again at the state)
  }
}

void World::give_back(const IntegrationGroup& g, bool impacted) {
  GroupShareWork& share = work_.share;
  if (impacted) {  // its new islands, gathered below in place of its old ones
    for (const std::size_t k : g.islands) share.island_replaced[k] = 1;
    for (const ContactIsland& island : state_.islands)
      share.joined_islands.push_back(append_island(island, state_.resting, share.joined_resting));
  } else {  // the same contacts, each island where it was (their order within it may have changed)
    for (std::size_t j = 0; j < g.islands.size(); ++j) {
      const ContactIsland& now = state_.islands[j];
      ContactIsland& was = share.all_islands[g.islands[j]];
      std::copy(state_.resting.begin() + static_cast<std::ptrdiff_t>(now.begin),
                state_.resting.begin() + static_cast<std::ptrdiff_t>(now.end),
                share.all_resting.begin() + static_cast<std::ptrdiff_t>(was.begin));
      was.live = now.live;
      was.clamped = now.clamped;
      was.asleep = now.asleep;
    }
  }
  // The features still watched are the group's in their order, less those its impacts made
  // contacts (all of them after max_collisions_per_step).
  std::size_t still = 0;
  for (const std::size_t k : g.watched) {
    if (still < state_.watched.size() && state_.watched[still] == share.all_watched[k]) {
      share.all_gaps[k] = state_.watched_gaps[still++];
    } else {
      share.watched_gone[k] = 1;
    }
  }
}

void World::gather_groups(bool any_impacted) {
  GroupShareWork& share = work_.share;
  state_.watched.clear();
  state_.watched_gaps.clear();
  for (std::size_t k = 0; k < share.all_watched.size(); ++k)
    if (!share.watched_gone[k])
      state_.watched.push_back(share.all_watched[k]), state_.watched_gaps.push_back(share.all_gaps[k]);
  if (!any_impacted) {  // every island where it was
    state_.resting.swap(share.all_resting);
    state_.islands.swap(share.all_islands);
    return;
  }
  // The islands of groups without impacts and of sleeping ones as they were, the impacted groups'
  // new ones, in the order of their lowest dynamic body (IslandGrouping's): a step that finds
  // the same contacts again finds them in the same places.
  const auto lowest_body = [&](const std::vector<ActiveContact>& resting, const ContactIsland& island) {
    int lowest = static_cast<int>(model_.bodies.size());
    for (std::size_t c = island.begin; c < island.end; ++c)
      for (const int i : {resting[c].feature.a, resting[c].feature.b})
        if (model_.slot[i] >= 0) lowest = std::min(lowest, i);
    return lowest;
  };
  share.island_order.clear();
  for (std::size_t k = 0; k < share.joined_islands.size(); ++k)
    share.island_order.push_back({lowest_body(share.joined_resting, share.joined_islands[k]), true, k});
  for (std::size_t k = 0; k < share.all_islands.size(); ++k)
    if (!share.island_replaced[k])
      share.island_order.push_back({lowest_body(share.all_resting, share.all_islands[k]), false, k});
  std::sort(share.island_order.begin(), share.island_order.end());
  state_.resting.clear();
  share.gathered_islands.clear();
  for (const auto& place : share.island_order) {
    const std::vector<ActiveContact>& from = place.joined ? share.joined_resting : share.all_resting;
    const ContactIsland& island = place.joined ? share.joined_islands[place.index] : share.all_islands[place.index];
    share.gathered_islands.push_back(append_island(island, from, state_.resting));
  }
  state_.islands.swap(share.gathered_islands);
}

}  // namespace wysiwyf::haptics
