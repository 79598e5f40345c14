// frame_latency against a case with a known answer: frames every 10 ms whose composites arrive
// three frames (30 ms) later, every tenth never composited, the tracker's pose 2 ms after its
// frame; the warm-up and the frames in flight at the stop are left out.
#include <gtest/gtest.h>

#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

TEST(FrameLatency, CompositesThreeFramesLateReadThreeFramesAndTheLostOnesAreCounted) {
  constexpr std::int64_t kMs = 1'000'000;
  const std::string summary = std::string(WYSIWYF_TEST_SCRATCH_DIR) + "/frame_latency.json";
  std::filesystem::create_directories(WYSIWYF_TEST_SCRATCH_DIR);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("frame_latency", "{summary: " + summary + ", warmup: 0.5, in_flight: 0.2}", 1000, &loader);
  auto frames = h.feed<msg::CameraInfo>("camera_info");
  auto shown = h.feed<msg::Image>("shown");
  auto tracker = h.feed<msg::PoseStamped>("tracker");
  h.activate();
  msg::CameraInfo info;
  msg::Image composite;
  msg::PoseStamped pose;
  const int n = 200;  // frames 0..199 over 2 s
  for (std::int64_t t = 0; t <= (n + 3) * 10 * kMs; t += kMs) {
    if (t % (10 * kMs) == 0) {
      const std::int64_t k = t / (10 * kMs);
      if (k < n) info.header().stamp_ns(t), frames.write(info);
      if (k >= 3 && k - 3 < n && (k - 3) % 10 != 0)  // frame k - 3's composite, unless it was lost
        composite.header().stamp_ns(t - 30 * kMs), shown.write(composite);
    }
    if (t % (10 * kMs) == 2 * kMs && t / (10 * kMs) < n) pose.header().stamp_ns(t - 2 * kMs), tracker.write(pose);
    h.tick(Time{t});
  }
  h.deactivate();
  const YAML::Node s = YAML::LoadFile(summary);
  // Counted: frames from 0.5 s (50) to 1.99 - 0.2 s (179): 130, of which 13 (50, 60, ..., 170) lost.
  EXPECT_EQ(s["frames"].as<int>(), 130);
  EXPECT_EQ(s["dropped"].as<int>(), 13);
  EXPECT_NEAR(s["camera_to_composite_ms"]["p50"].as<double>(), 30.0, 1e-9);
  EXPECT_NEAR(s["camera_to_composite_ms"]["p99"].as<double>(), 30.0, 1e-9);
  EXPECT_NEAR(s["camera_to_tracker_ms"]["p50"].as<double>(), 2.0, 1e-9);
}

}  // namespace wysiwyf::test
