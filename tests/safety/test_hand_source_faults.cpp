// hand_tracker_sim's faults that the safety campaign draws: a glitch (the position off by a fixed
// offset for a while) and stale stamps (positions published as if seen earlier), each confined to
// its window.
#include <gtest/gtest.h>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::safety {
namespace {

struct Published {
  Eigen::Vector3d position;
  std::int64_t stamp_ns;
};

// The hand still at (0.9, 0.1, 0.2); what the tracker publishes at 100 Hz over 0.5 s.
std::vector<Published> track(const std::string& params) {
  Harness h("hand_tracker_sim", params, 100);
  auto in = h.feed<msg::PoseStamped>("hand_pose");
  auto out = h.watch<msg::HandPosition>("hand");
  h.activate();
  std::vector<Published> seen;
  for (int i = 0; i <= 50; ++i) {
    const std::int64_t t = i * 10'000'000LL;
    msg::PoseStamped p;
    fill_header(p.header(), t, static_cast<std::uint64_t>(i), "base");
    msgs::to_msg(Eigen::Isometry3d(Eigen::Translation3d(0.9, 0.1, 0.2)), p.pose());
    in.write(p);
    h.tick(Time{t});
    for (msg::HandPosition m; out.take(m);) seen.push_back({msgs::to_eigen(m.position()), m.header().stamp_ns()});
  }
  return seen;
}

TEST(HandSourceFaults, AGlitchOffsetsThePositionWithinItsWindowOnly) {
  const auto seen = track("{noise: 0, latency: 0, glitches: [0.1, 0.2, 0.0, 0.0, 0.1]}");
  ASSERT_EQ(seen.size(), 51u);
  for (const auto& s : seen) {
    const double t = s.stamp_ns * 1e-9;
    const double z = t >= 0.1 - 1e-9 && t < 0.2 - 1e-9 ? 0.3 : 0.2;
    EXPECT_NEAR(s.position.z(), z, 1e-9) << t;
  }
}

TEST(HandSourceFaults, StaleStampsAreOlderWithinTheirWindowOnly) {
  const auto seen = track("{noise: 0, latency: 0, stale: [0.3, 0.4, 0.25]}");
  ASSERT_EQ(seen.size(), 51u);
  for (std::size_t i = 0; i < seen.size(); ++i) {
    const std::int64_t t = static_cast<std::int64_t>(i) * 10'000'000LL;
    const bool stale = t >= 300'000'000 && t < 400'000'000;
    EXPECT_EQ(seen[i].stamp_ns, stale ? t - 250'000'000 : t) << i;
  }
}

}  // namespace
}  // namespace wysiwyf::safety
