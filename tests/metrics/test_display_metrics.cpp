// display_metrics against cases with a known answer: a plate deliberately off the virtual
// feature by a set distance and turn reads that distance and turn, at the touch and over an
// attachment to a moving object, with the onset window and the percentiles where they must be.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {

namespace {

constexpr std::int64_t kMs = 1'000'000;
const std::string kFeature = "cube +x knob";

// The cube sliding along +x at 0.1 m/s (the push), from x = 0.6.
Eigen::Isometry3d base_T_cube(double t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.6 + 0.1 * t, 0.0, 0.1);
  return T;
}

}  // namespace

TEST(DisplayMetrics, APlateOffByKnownAmountsReadsThemAtTheTouchAndWhileAttached) {
  const haptics::Scene scene = haptics::load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/scenes/display_demo.yaml");
  const haptics::DisplayFeature* feature = scene.feature(kFeature);
  ASSERT_NE(feature, nullptr);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, onset_window: 0.1}", 1000, &loader);
  auto device = h.feed<msg::PoseStamped>("device_pose");
  auto objects = h.feed<msg::ObjectState>("objects");
  auto events = h.feed<msg::UserEvent>("events");
  auto attach = h.feed<msg::Attachment>("attach");
  auto contacts = h.watch<msg::ContactReport>("contacts");
  auto registration = h.watch<msg::HapticRegistration>("registration");
  h.activate();

  // The plate 2 mm along its own x and turned 0.5 deg about its normal from the feature's pose,
  // 3 mm in the first 100 ms attached (0.1 s to 0.2 s): the onset, the arm lagging the push.
  const double turn = 0.5 * M_PI / 180;
  const auto plate = [&](double t) {
    const double off = t >= 0.1 - 1e-9 && t <= 0.2 + 1e-9 ? 0.003 : 0.002;
    return base_T_cube(t) * feature->obj_T_plate * Eigen::Translation3d(off, 0, 0) *
           Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ());
  };
  for (int k = 0; k <= 1000; ++k) {
    const double t = k * 1e-3;
    const std::int64_t ns = k * kMs;
    msg::ObjectState cube;
    fill_header(cube.header(), ns, static_cast<std::uint64_t>(k), "base");
    cube.child_frame_id("cube");
    msgs::to_msg(base_T_cube(t), cube.pose());
    objects.write(cube);
    msg::PoseStamped d;
    fill_header(d.header(), ns, static_cast<std::uint64_t>(k), "base");
    msgs::to_msg(plate(t), d.pose());
    device.write(d);
    if (k == 90) {  // the finger arrives
      msg::UserEvent e;
      fill_header(e.header(), ns, 0, "base");
      e.kind(msg::USER_TOUCH);
      e.contact(1);
      e.feature(kFeature);
      e.body("cube");
      events.write(e);
    }
    if (k == 100 || k == 900) {  // the supervisor attaches, then lets go
      msg::Attachment a;
      fill_header(a.header(), ns, static_cast<std::uint64_t>(k), "base");
      a.attached(k == 100);
      a.body("cube");
      a.feature(kFeature);
      msgs::to_msg(feature->obj_T_plate, a.obj_T_dev());
      attach.write(a);
    }
    h.tick(Time{ns});
  }
  h.deactivate();

  msg::ContactReport c;
  ASSERT_TRUE(contacts.take(c));
  EXPECT_TRUE(c.hit());
  EXPECT_EQ(c.contact(), 1u);
  EXPECT_NEAR(c.offset_mm(), 2.0, 1e-6);
  EXPECT_NEAR(c.angle_deg(), 0.5, 1e-6);

  msg::HapticRegistration r;
  ASSERT_TRUE(registration.take(r));
  EXPECT_EQ(r.contact(), 1u);
  EXPECT_EQ(std::string(r.feature().c_str()), kFeature);
  // 0.1 s to 0.9 s at 1 kHz: 801 samples, 101 of them (0.1 s to 0.2 s) 3 mm off, 700 2 mm off.
  EXPECT_EQ(r.samples(), 801u);
  EXPECT_NEAR(r.p50_mm(), 2.0, 1e-6);
  EXPECT_NEAR(r.p99_mm(), 3.0, 1e-6);  // rank 793 of 801 lies among the 3 mm ones
  EXPECT_NEAR(r.max_mm(), 3.0, 1e-6);
  EXPECT_NEAR(r.max_deg(), 0.5, 1e-6);
  EXPECT_NEAR(r.onset_max_mm(), 3.0, 1e-6);
  EXPECT_NEAR(r.onset_max_deg(), 0.5, 1e-6);
  EXPECT_FALSE(registration.take(r)) << "one attachment, one report";
}

TEST(DisplayMetrics, AnAttachmentToAnUnknownBodyIsRefusedNotMeasured) {
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml}", 1000, &loader);
  auto attach = h.feed<msg::Attachment>("attach");
  auto registration = h.watch<msg::HapticRegistration>("registration");
  h.activate();
  msg::Attachment a;
  fill_header(a.header(), kMs, 0, "base");
  a.attached(true);
  a.body("no such body");
  msgs::to_msg(Eigen::Isometry3d::Identity(), a.obj_T_dev());
  attach.write(a);
  h.tick(Time{kMs});
  a.attached(false);
  attach.write(a);
  h.tick(Time{2 * kMs});
  h.deactivate();
  msg::HapticRegistration r;
  EXPECT_FALSE(registration.take(r));
  EXPECT_EQ(h.rejected("attach"), 1u);
}

}  // namespace wysiwyf::test
