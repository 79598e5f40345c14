// frame_latency: how long each camera frame takes to reach the tracker's pose and the composite,
// and how many frames never reach the composite. Every stage stamps its output with the camera
// frame's stamp (capture time); this component notes when each output arrives (its tick time:
// trigger it on all its inputs, so it ticks on arrival) and subtracts. On the real clock that is
// the vision path's latency as a viewer would see it; on the sim clock, sim time.
#include <cstdio>
#include <fstream>
#include <map>

#include "stats/percentiles.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::display {

using stats::Percentiles;

class FrameLatency final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("camera frame to tracker pose and to composite: latency p50/p99/max and frames never composited");
    summary_path_ = ctx.param<std::string>("summary", "", "JSON file written at the end (empty: none)");
    warmup_s_ = ctx.param<double>(
        "warmup", 1.0, "s from the first frame not counted (start-up: the tracker's first fix)", Range{0, 60});
    in_flight_s_ = ctx.param<double>(
        "in_flight", 0.2, "s before the last frame: frames this recent at the stop are not counted as dropped",
        Range{0, 10});
    frames_in_ = ctx.input<msg::CameraInfo>("camera_info", "sent with every camera frame: its stamp names the frame",
                                            Qos::reliable(64));
    shown_in_ = ctx.input<msg::Image>(
        "shown", "the compositor's `shown` (publish_shown: true): stamped with the camera frame its composite shows",
        Qos::reliable(16));
    tracker_in_ = ctx.input<msg::PoseStamped>("tracker", "optional: the tracker's eye_T_base, stamped with its frame",
                                              Qos::reliable(64).optional_input());
  }

  void tick(Time now) override {
    while (frames_in_.take(info_)) {
      const std::int64_t stamp = info_.header().stamp_ns();
      if (first_frame_ < 0) first_frame_ = stamp;
      frames_.emplace(stamp, Frame{});
      last_frame_ = std::max(last_frame_, stamp);
    }
    while (tracker_in_.take(pose_)) arrived(pose_.header().stamp_ns(), now, &Frame::tracked, tracker_ms_);
    while (shown_in_.take(shown_)) arrived(shown_.header().stamp_ns(), now, &Frame::composited, composite_ms_);
  }

  void deactivate() override {
    std::size_t counted = 0, dropped = 0, composited = 0;
    for (const auto& [stamp, f] : frames_) {
      if (!counts(stamp)) continue;
      ++counted;
      if (!f.composited) ++dropped;
      composited += f.composited ? 1 : 0;
    }
    char line[256];
    std::snprintf(line, sizeof line,
                  "camera to composite: p50 %.2f ms, p99 %.2f ms, max %.2f ms over %zu frames; %zu of %zu frames "
                  "never composited; camera to tracker pose: p50 %.2f ms, p99 %.2f ms",
                  composite_ms_.percentile(50), composite_ms_.percentile(99), composite_ms_.max(), composited, dropped,
                  counted, tracker_ms_.percentile(50), tracker_ms_.percentile(99));
    log(line);
    if (summary_path_.empty()) return;
    std::ofstream out(summary_path_);
    out << "{\n  \"frames\": " << counted << ",\n  \"composited\": " << composited << ",\n  \"dropped\": " << dropped
        << ",\n  \"camera_to_composite_ms\": " << figures(composite_ms_)
        << ",\n  \"camera_to_tracker_ms\": " << figures(tracker_ms_) << "\n}\n";
    if (!out) warn_once("summary", "could not write " + summary_path_);
  }

 private:
  struct Frame {
    bool tracked = false, composited = false;
  };

  // After the warm-up, and not in flight at the stop.
  bool counts(std::int64_t stamp) const {
    return stamp >= first_frame_ + static_cast<std::int64_t>(warmup_s_ * 1e9) &&
           stamp <= last_frame_ - static_cast<std::int64_t>(in_flight_s_ * 1e9);
  }

  void arrived(std::int64_t stamp, Time now, bool Frame::*stage, Percentiles& ms) {
    const auto it = frames_.find(stamp);
    if (it == frames_.end() || it->second.*stage) return;  // before the first frame seen, or a repeat
    it->second.*stage = true;
    if (stamp >= first_frame_ + static_cast<std::int64_t>(warmup_s_ * 1e9))
      ms.add(static_cast<double>(elapsed_ns(now.ns, stamp)) * 1e-6, stamp);
  }

  static std::string figures(const Percentiles& p) {
    char s[160];
    std::snprintf(s, sizeof s, "{\"samples\": %zu, \"p50\": %.3f, \"p99\": %.3f, \"max\": %.3f}", p.samples(),
                  p.percentile(50), p.percentile(99), p.max());
    return s;
  }

  std::string summary_path_;
  double warmup_s_ = 1.0, in_flight_s_ = 0.2;
  std::int64_t first_frame_ = -1, last_frame_ = -1;
  std::map<std::int64_t, Frame> frames_;
  Percentiles composite_ms_, tracker_ms_;
  msg::CameraInfo info_;
  msg::Image shown_;
  msg::PoseStamped pose_;
  Input<msg::CameraInfo> frames_in_;
  Input<msg::Image> shown_in_;
  Input<msg::PoseStamped> tracker_in_;
};

}  // namespace wysiwyf::display

WYSIWYF_COMPONENT(wysiwyf::display::FrameLatency, "frame_latency")
