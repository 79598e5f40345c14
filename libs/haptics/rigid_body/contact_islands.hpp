#pragma once
// Grouping contacts by island (world_state.hpp's ContactIsland): union-find over the dynamic
// bodies that the contacts join, then a stable reordering that makes each island's contacts
// contiguous. Scratch kept between calls, so that grouping does not allocate once sizes settle.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "rigid_body/union_find.hpp"
#include "rigid_body/world_state.hpp"

namespace wysiwyf::haptics {

class IslandGrouping {
 public:
  // Reorders `contacts` so that each island's are contiguous (in their order within it; islands
  // in the order of their lowest body) and writes one range per island. `slot`: body -> dynamic
  // index or -1 (WorldModel::slot). `previous`: the contacts the islands' warm starts (their
  // clamped sets) index into; each contact clamped there is clamped in its new island's warm
  // start, and each one still touching takes its friction along (the start of the next friction
  // rounds, which settle in one or two from it, where contacts came or went elsewhere too).
  // Where the contacts are the same, in the same places, the caller carries both as they are.
  // (The LCP checks a warm start and goes on from what of it holds: a wrong one costs only
  // pivots, so an island whose contacts come and go keeps the warm start of those it still has
  // rather than pivoting from nothing.)
  void group(std::vector<ActiveContact>& contacts, const std::vector<int>& slot, std::vector<ContactIsland>& islands,
             const std::vector<ActiveContact>& previous);

 private:
  UnionFind bodies_;
  std::vector<std::pair<int, std::size_t>> order_;  // (island root, position) per contact
  std::vector<ActiveContact> sorted_;
  std::vector<ContactIsland> previous_;
  std::vector<std::pair<std::uint64_t, std::size_t>> by_feature_;  // (feature's key, position), sorted
  std::vector<std::size_t> island_of_;                             // per position: its island
};

}  // namespace wysiwyf::haptics
