// The surface planner alone (the Harness) against hostile hand samples: one stamped far ahead of
// the pipeline's clock is rejected (kept, it would leave the hand "known" long after it is gone,
// and a wrapped difference of stamps would say so for ever); one in another frame than base (a
// stereo tracker's first sample, before it knows the camera's pose) is rejected; one stamped now,
// in base, is taken.
#include <gtest/gtest.h>

#include <limits>

#include "display_support.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(PlannerInputs, AHandStampedFarAheadIsRejectedAndAHandStampedNowIsTaken) {
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("surface_planner", "{scene: scenes/display_demo.yaml}", 1000, &loader);
  auto joints = h.feed<msg::JointState>("joint_state");
  auto device = h.feed<msg::PoseStamped>("device_pose");
  auto mode = h.feed<msg::DisplayMode>("mode");
  auto hand = h.feed<msg::HandPosition>("hand");
  auto status = h.watch<msg::PlannerStatus>("status");
  h.activate();
  const double parked[6] = {0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254};  // hardware/sim.yaml
  Eigen::Isometry3d plate = Eigen::Isometry3d::Identity();
  plate.translation() = Eigen::Vector3d(0.55, 0, 0.4);
  // The last status of ticks [from, to) ms, with a hand stamped `hand_stamp` written at `from`.
  auto run = [&](std::int64_t from, std::int64_t to, std::int64_t hand_stamp, const char* frame = "base") {
    msg::PlannerStatus last;
    for (std::int64_t t_ms = from; t_ms < to; ++t_ms) {
      const std::int64_t t = t_ms * kMs;
      msg::JointState j;
      fill_header(j.header(), t, 0, "base");
      j.position().resize(6);
      for (int i = 0; i < 6; ++i) j.position()[static_cast<std::size_t>(i)] = parked[i];
      joints.write(j);
      msg::PoseStamped d;
      fill_header(d.header(), t, 0, "base");
      msgs::to_msg(plate, d.pose());
      device.write(d);
      msg::DisplayMode m;
      m.mode(msg::MODE_SURFACE);
      mode.write(m);
      if (t_ms == from) {
        msg::HandPosition p;
        fill_header(p.header(), hand_stamp, 0, frame);
        msgs::to_msg(Eigen::Vector3d(0.95, -0.1, 0.15), p.position());
        for (std::size_t i = 0; i < 9; i += 4) p.covariance()[i] = 1e-4;
        p.status(msg::TRACKING_OK);
        hand.write(p);
      }
      h.tick(Time{t});
      while (status.take(last)) {
      }
    }
    return last;
  };
  const msg::PlannerStatus ahead = run(1, 50, std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(h.rejected("hand"), 1u);
  EXPECT_STREQ(ahead.reason().c_str(), "no hand in view");
  const msg::PlannerStatus in_eye = run(50, 100, 50 * kMs, "eye");
  EXPECT_EQ(h.rejected("hand"), 2u);
  EXPECT_STREQ(in_eye.reason().c_str(), "no hand in view");
  const msg::PlannerStatus now = run(100, 150, 100 * kMs);
  EXPECT_EQ(h.rejected("hand"), 2u) << "a hand stamped now, in base, is taken";
  EXPECT_STRNE(now.reason().c_str(), "no hand in view");
  EXPECT_FALSE(std::string(now.feature().c_str()).empty()) << "a feature is chosen for the taken hand";
}

}  // namespace
}  // namespace wysiwyf::test
