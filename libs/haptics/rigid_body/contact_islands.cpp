#include "rigid_body/contact_islands.hpp"

#include <algorithm>

namespace wysiwyf::haptics {

void IslandGrouping::group(std::vector<ActiveContact>& contacts, const std::vector<int>& slot,
                           std::vector<ContactIsland>& islands, const std::vector<ActiveContact>& previous) {
  bodies_.reset(slot.size());
  for (const auto& c : contacts)
    if (joins_dynamic_bodies(c.feature, slot)) bodies_.join(c.feature.a, c.feature.b);
  order_.clear();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    order_.emplace_back(bodies_.root(dynamic_body(contacts[i].feature, slot)), i);
  }
  std::sort(order_.begin(), order_.end());  // by island, then by position: stable within each
  sorted_.clear();
  for (const auto& [island, i] : order_) sorted_.push_back(contacts[i]);
  contacts.swap(sorted_);

  // The islands, each with its contacts' place in the previous islands' warm starts.
  previous_.swap(islands);
  islands.clear();
  island_of_.resize(contacts.size());
  for (std::size_t i = 0; i < contacts.size();) {
    std::size_t end = i + 1;
    while (end < contacts.size() && order_[end].first == order_[i].first) ++end;
    ContactIsland island;
    island.begin = i, island.end = end, island.live = end - i;
    std::fill(island_of_.begin() + static_cast<std::ptrdiff_t>(i),
              island_of_.begin() + static_cast<std::ptrdiff_t>(end), islands.size());
    islands.push_back(island);
    i = end;
  }
  // The same contacts in the same places (a resting scene): the warm starts stay as they are.
  const bool same = islands.size() == previous_.size() && contacts.size() == previous.size() &&
                    std::equal(islands.begin(), islands.end(), previous_.begin(),
                               [](const ContactIsland& x, const ContactIsland& y) { return x.end == y.end; }) &&
                    std::equal(contacts.begin(), contacts.end(), previous.begin(),
                               [](const ActiveContact& x, const ActiveContact& y) { return x.feature == y.feature; });
  if (same) {
    for (std::size_t k = 0; k < islands.size(); ++k) islands[k].clamped = previous_[k].clamped;
    return;
  }
  by_feature_.clear();
  for (std::size_t i = 0; i < contacts.size(); ++i) by_feature_.emplace_back(feature_key(contacts[i].feature), i);
  std::sort(by_feature_.begin(), by_feature_.end());
  const auto now_at = [&](const ContactFeature& f) -> const std::pair<std::uint64_t, std::size_t>* {
    const std::uint64_t key = feature_key(f);
    const auto found = std::lower_bound(by_feature_.begin(), by_feature_.end(), std::make_pair(key, std::size_t{0}));
    return found == by_feature_.end() || found->first != key ? nullptr : &*found;
  };
  // Each contact still touching starts the step's friction rounds from the friction it held
  // (update_friction takes it onto its new tangents).
  for (const ActiveContact& was : previous)
    if (!was.friction.isZero(0.0))
      if (const auto* found = now_at(was.feature)) contacts[found->second].friction = was.friction;
  for (const ContactIsland& was : previous_)
    for (const int c : was.clamped) {
      const std::size_t at = was.begin + static_cast<std::size_t>(c);
      if (c < 0 || at >= was.end || at >= previous.size()) continue;  // (not a set of those contacts)
      const auto* found = now_at(previous[at].feature);
      if (found == nullptr) continue;  // no longer touching
      ContactIsland& now = islands[island_of_[found->second]];
      if (now.clamped.size() >= kMaxLcpSize) continue;  // (an island the LCP will refuse anyway)
      now.clamped.conservativeResize(now.clamped.size() + 1);
      now.clamped[now.clamped.size() - 1] = static_cast<int>(found->second - now.begin);
    }
}

}  // namespace wysiwyf::haptics
