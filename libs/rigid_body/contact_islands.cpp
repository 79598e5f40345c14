#include "rigid_body/contact_islands.hpp"

#include <algorithm>
#include <numeric>

namespace wysiwyf::haptics {

int IslandGrouping::root(int body) {
  while (parent_[static_cast<std::size_t>(body)] != body) {
    auto& p = parent_[static_cast<std::size_t>(body)];
    p = parent_[static_cast<std::size_t>(p)];  // path halving
    body = p;
  }
  return body;
}

void IslandGrouping::group(std::vector<ActiveContact>& contacts, const std::vector<int>& slot,
                           std::vector<ContactIsland>& islands) {
  parent_.resize(slot.size());
  std::iota(parent_.begin(), parent_.end(), 0);
  for (const auto& c : contacts)
    if (slot[c.feature.a] >= 0 && slot[c.feature.b] >= 0) {
      const int ra = root(c.feature.a), rb = root(c.feature.b);
      if (ra != rb) parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
    }
  order_.clear();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const ContactFeature& f = contacts[i].feature;
    order_.emplace_back(root(slot[f.a] >= 0 ? f.a : f.b), i);
  }
  std::sort(order_.begin(), order_.end());  // by island, then by position: stable within each
  sorted_.clear();
  for (const auto& [island, i] : order_) sorted_.push_back(contacts[i]);
  contacts.swap(sorted_);

  // The islands, each with the warm start of the island in its place if that had as many contacts.
  previous_.swap(islands);
  islands.clear();
  for (std::size_t i = 0; i < contacts.size();) {
    std::size_t end = i + 1;
    while (end < contacts.size() && order_[end].first == order_[i].first) ++end;
    ContactIsland island;
    island.begin = i, island.end = end, island.live = end - i;
    islands.push_back(island);
    i = end;
  }
  for (std::size_t k = 0; k < islands.size() && k < previous_.size(); ++k)
    if (previous_[k].end - previous_[k].begin == islands[k].end - islands[k].begin)
      islands[k].clamped = previous_[k].clamped;
}

}  // namespace wysiwyf::haptics
