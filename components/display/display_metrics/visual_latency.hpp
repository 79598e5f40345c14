#pragma once
// Visual latency: for every composite, how long after its camera frame was taken it was made
// (sim time). The compositor's `composite` carries when it was made, its `shown` alpha the stamp
// of the camera frame it was made from; the two are matched by seq. The frames' times are kept a
// while for the contact timing (when the user first saw a touch).
#include <cstddef>
#include <cstdint>
#include <deque>
#include <ostream>
#include <string>
#include <utility>

#include "run_report.hpp"
#include "stats/percentiles.hpp"
#include "wysiwyf/kernel_msgs.hpp"

namespace wysiwyf::display {

class VisualLatency {
 public:
  struct Frame {
    std::int64_t taken;  // the camera frame's stamp
    std::int64_t made;   // when its composite was made
  };

  // A composite: its seq and when it was made.
  void add_composite(std::uint64_t seq, std::int64_t made_ns);
  // A shown alpha's header (seq and camera stamp): matched to its composite, each latency added to
  // the run report's latency.csv when there is one.
  void measure(const std_msgs::Header& shown, RunReport* report);
  // Drops the frames taken before t.
  void forget_before(std::int64_t t);

  const std::deque<Frame>& frames() const { return frames_; }
  // The time between the last two camera frames (0 with fewer than two).
  std::int64_t frame_period() const;

  // The run's figures, for the log; empty without any image.
  std::string end_line() const;
  // The summary's "visual_latency" member.
  void write_json(std::ostream& j) const;

 private:
  static constexpr std::size_t kCompositesKept = 16;
  std::deque<std::pair<std::uint64_t, std::int64_t>> made_at_;  // composite seq, its stamp
  std::deque<Frame> frames_;
  stats::Percentiles ms_;
};

}  // namespace wysiwyf::display
