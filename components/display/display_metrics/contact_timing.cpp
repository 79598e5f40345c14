#include "contact_timing.hpp"

#include <algorithm>

#include "summary_json.hpp"

namespace wysiwyf::display {

void ContactTiming::touch(std::uint32_t contact, const std::string& feature, std::int64_t t) {
  Touch c;
  c.contact = contact;
  c.feature = feature;
  c.touch = t;
  touches_.push_back(c);
}

void ContactTiming::update(const VisualLatency& latency) {
  for (auto& c : touches_) {
    if (c.done) continue;
    if (c.force_at < 0) {
      // Only the samples not looked at yet (the stamps rise).
      const std::int64_t from = std::max(c.touch - 100'000'000, c.forces_seen_until + 1);
      auto it = std::lower_bound(forces_.begin(), forces_.end(), from,
                                 [](const auto& sample, std::int64_t t) { return sample.first < t; });
      for (; it != forces_.end(); ++it) {
        c.forces_seen_until = it->first;
        if (it->second > force_onset_) {
          c.force_at = it->first;
          break;
        }
      }
    }
    if (c.seen_at < 0)
      for (const VisualLatency::Frame& f : latency.frames())
        if (f.taken >= c.touch) {
          c.seen_at = f.made, c.frame_period = latency.frame_period();
          break;
        }
    c.done = c.force_at >= 0 && c.seen_at >= 0;
  }
}

void ContactTiming::forget_before(std::int64_t t) {
  while (!forces_.empty() && forces_.front().first < t) forces_.pop_front();
}

std::optional<double> ContactTiming::latest_force() const {
  if (forces_.empty()) return std::nullopt;
  return forces_.back().second;
}

std::vector<std::string> ContactTiming::end_lines() const {
  std::vector<std::string> lines;
  for (const auto& c : touches_)
    if (c.done)
      lines.push_back("contact " + std::to_string(c.contact) + " timing: the force rose " +
                      std::to_string(static_cast<double>(c.force_at - c.touch) * 1e-6) +
                      " ms after the touch, the user saw it " +
                      std::to_string(static_cast<double>(c.seen_at - c.touch) * 1e-6) + " ms after it");
  return lines;
}

void ContactTiming::write_json(std::ostream& j) const {
  j << "\"contact_timing\": [";
  bool first = true;
  for (const auto& c : touches_) {
    if (!c.done) continue;
    const double ms = static_cast<double>(c.seen_at - c.force_at) * 1e-6;
    j << (first ? "" : ",") << "\n    {\"contact\": " << c.contact << ", \"feature\": " << json_quoted(c.feature)
      << ", \"force_rise_after_touch_ms\": " << json_number(static_cast<double>(c.force_at - c.touch) * 1e-6)
      << ", \"seen_after_touch_ms\": " << json_number(static_cast<double>(c.seen_at - c.touch) * 1e-6)
      << ", \"seen_after_force_ms\": " << json_number(ms) << ", \"seen_after_force_frames\": "
      << json_number(c.frame_period > 0 ? ms * 1e6 / static_cast<double>(c.frame_period) : -1) << "}";
    first = false;
  }
  j << (first ? "" : "\n  ") << "]";
}

}  // namespace wysiwyf::display
