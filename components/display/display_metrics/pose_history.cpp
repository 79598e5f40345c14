#include "pose_history.hpp"

#include <algorithm>

namespace wysiwyf::display {

const PoseSample* pose_at(const PoseTrack& track, std::int64_t t) {
  if (track.empty()) return nullptr;
  const auto after =
      std::upper_bound(track.begin(), track.end(), t, [](std::int64_t v, const PoseSample& s) { return v < s.t; });
  return after == track.begin() ? &track.front() : &*(after - 1);
}

void PoseHistory::forget_before(std::int64_t now_ns) {
  while (!plate_.empty() && plate_.front().t < now_ns - history_ns_) plate_.pop_front();
  for (auto& track : objects_)
    while (track.size() > 1 && track[1].t < now_ns - history_ns_) track.pop_front();
}

}  // namespace wysiwyf::display
