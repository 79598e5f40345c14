#include "visual_latency.hpp"

#include "summary_json.hpp"

namespace wysiwyf::display {

void VisualLatency::add_composite(std::uint64_t seq, std::int64_t made_ns) {
  made_at_.emplace_back(seq, made_ns);
  if (made_at_.size() > kCompositesKept) made_at_.pop_front();
}

void VisualLatency::measure(const std_msgs::Header& shown, RunReport* report) {
  for (const auto& [seq, made] : made_at_) {
    const std::int64_t frame = shown.stamp_ns();
    if (seq != shown.seq() || made < frame) continue;
    frames_.push_back({frame, made});
    ms_.add(static_cast<double>(made - frame) * 1e-6, frame);
    if (report) report->latency(static_cast<double>(made) * 1e-9, static_cast<double>(made - frame) * 1e-6);
  }
}

void VisualLatency::forget_before(std::int64_t t) {
  while (!frames_.empty() && frames_.front().taken < t) frames_.pop_front();
}

std::int64_t VisualLatency::frame_period() const {
  return frames_.size() > 1 ? frames_.back().taken - frames_[frames_.size() - 2].taken : 0;
}

std::string VisualLatency::end_line() const {
  if (ms_.samples() == 0) return "";
  return "visual latency, camera frame to composite (sim time): p50 " + std::to_string(ms_.percentile(50)) +
         " ms, max " + std::to_string(ms_.max()) + " ms over " + std::to_string(ms_.samples()) + " images";
}

void VisualLatency::write_json(std::ostream& j) const {
  j << "\"visual_latency\": {\"images\": " << ms_.samples() << ", " << json_figures(ms_, "ms", "camera_to_composite_")
    << "}";
}

}  // namespace wysiwyf::display
