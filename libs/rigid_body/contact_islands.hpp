#pragma once
// Grouping contacts by island (world_state.hpp's ContactIsland): union-find over the dynamic
// bodies that the contacts join, then a stable reordering that makes each island's contacts
// contiguous. Scratch kept between calls, so that grouping does not allocate once sizes settle.
#include <cstddef>
#include <utility>
#include <vector>

#include "rigid_body/world_state.hpp"

namespace wysiwyf::haptics {

class IslandGrouping {
 public:
  // Reorders `contacts` so that each island's are contiguous (in their order within it; islands
  // in the order of their lowest body) and writes one range per island. `slot`: body -> dynamic
  // index or -1 (WorldModel::slot). Each island keeps the warm start of the island that was in
  // its place with as many contacts (the LCP checks a warm start: a wrong one costs only pivots).
  void group(std::vector<ActiveContact>& contacts, const std::vector<int>& slot, std::vector<ContactIsland>& islands);

 private:
  int root(int body);

  std::vector<int> parent_;                         // union-find over body indices
  std::vector<std::pair<int, std::size_t>> order_;  // (island root, position) per contact
  std::vector<ActiveContact> sorted_;
  std::vector<ContactIsland> previous_;
};

}  // namespace wysiwyf::haptics
