#pragma once
// Union-find over the indices 0..n-1 (path halving): the connected sets of bodies that contacts
// join (contact_islands.hpp's islands, integration_groups.hpp's groups). A joined set's root is
// its lowest index.
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace wysiwyf::haptics {

class UnionFind {
 public:
  // Every index alone again (the storage is kept).
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int root(int i) {
    while (parent_[static_cast<std::size_t>(i)] != i) {
      auto& p = parent_[static_cast<std::size_t>(i)];
      p = parent_[static_cast<std::size_t>(p)];
      i = p;
    }
    return i;
  }
  void join(int a, int b) {
    const int ra = root(a), rb = root(b);
    if (ra != rb) parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace wysiwyf::haptics
