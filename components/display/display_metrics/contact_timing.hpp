#pragma once
// Contact timing: per touch, when the user's force rose past force_onset (looked for from 0.1 s
// before the touch) and when the user first saw the finger there (the first composite of a camera
// frame taken at or after the touch): ms and frames. Positive: the eye learns later than the hand.
#include <cstdint>
#include <deque>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "visual_latency.hpp"

namespace wysiwyf::display {

class ContactTiming {
 public:
  // force_onset: N, the user's force from which a contact is felt.
  explicit ContactTiming(double force_onset = 1.0) : force_onset_(force_onset) {}

  // The user touched `feature` at t.
  void touch(std::uint32_t contact, const std::string& feature, std::int64_t t);
  // The user's force (N) at t; stamps rise.
  void add_force(std::int64_t t, double newton) { forces_.emplace_back(t, newton); }
  // Times every touch not yet timed, with the forces so far and the frames `latency` has matched.
  void update(const VisualLatency& latency);
  // Drops the forces before t.
  void forget_before(std::int64_t t);

  // The latest force kept (for the time series).
  std::optional<double> latest_force() const;
  // One log line per timed touch.
  std::vector<std::string> end_lines() const;
  // The summary's "contact_timing" member.
  void write_json(std::ostream& j) const;

 private:
  struct Touch {
    std::uint32_t contact = 0;
    std::string feature;
    std::int64_t touch = 0, force_at = -1, seen_at = -1, frame_period = 0;
    std::int64_t forces_seen_until = -1;  // the newest force sample looked at
    bool done = false;
  };
  double force_onset_;
  std::deque<std::pair<std::int64_t, double>> forces_;  // the user's force, N, by stamp
  std::vector<Touch> touches_;
};

}  // namespace wysiwyf::display
