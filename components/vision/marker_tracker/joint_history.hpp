#pragma once
// The arm's recent joint positions by stamp, so that an image is paired with the joints the
// arm had when it was taken (the device motion is the filter's known input).
#include <array>
#include <cstdint>
#include <cstdlib>

#include "arm_model/arm_types.hpp"

namespace wysiwyf::vision {

class JointHistory {
 public:
  static constexpr int kCapacity = 256;  // 0.256 s of a 1 kHz stream

  void add(std::int64_t stamp_ns, const robot::JointVector& q) {
    entries_[static_cast<std::size_t>(next_)] = Entry{stamp_ns, q};
    next_ = (next_ + 1) % kCapacity;
    if (size_ < kCapacity) ++size_;
  }
  // The sample nearest in time to stamp_ns (the newest of equals); false when there is none.
  bool at(std::int64_t stamp_ns, robot::JointVector& q) const {
    std::int64_t best = -1;
    for (int i = 0; i < size_; ++i) {
      const Entry& e = entries_[static_cast<std::size_t>((next_ - 1 - i + kCapacity) % kCapacity)];
      const std::int64_t gap = std::llabs(e.stamp_ns - stamp_ns);
      if (best < 0 || gap < best) best = gap, q = e.q;
    }
    return best >= 0;
  }
  bool empty() const { return size_ == 0; }

 private:
  struct Entry {
    std::int64_t stamp_ns = 0;
    robot::JointVector q;  // the arm's n joints, stored inline
  };
  std::array<Entry, kCapacity> entries_{};
  int next_ = 0, size_ = 0;
};

}  // namespace wysiwyf::vision
