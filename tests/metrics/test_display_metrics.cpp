// display_metrics against cases with a known answer: a plate deliberately off the virtual
// feature by a set distance and turn reads that distance and turn, at the touch and over an
// attachment to a moving object, with the onset window and the percentiles where they must be.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "scene/scene.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/validator.hpp"
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
  auto wrench = h.feed<msg::WrenchStamped>("wrench");
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
    {  // The wrist reading: the tool's weight, plus the user's 4 N push along the plate's normal
       // while attached, 7 N at one instant (the peak), and 30 N after letting go (not counted).
      const Eigen::Matrix3d base_R_sensor = plate(t).linear() * scene.device.dev_T_sensor.linear();
      const double user = k == 500 ? 7.0 : k > 100 && k < 900 ? 4.0 : k > 950 ? 30.0 : 0.0;
      const Eigen::Vector3d f =
          base_R_sensor.transpose() * (scene.device.tool_mass * scene.gravity - user * plate(t).linear().col(2));
      const Eigen::Vector3d torque =
          scene.device.tool_com.cross(base_R_sensor.transpose() * (scene.device.tool_mass * scene.gravity));
      msg::WrenchStamped w;
      fill_header(w.header(), ns, static_cast<std::uint64_t>(k), "ft_sensor");
      msgs::to_msg(f, torque, w.wrench());
      wrench.write(w);
    }
    if (k == 95) {  // the push begins, meant to be 4 N
      msg::UserEvent e;
      fill_header(e.header(), ns, 0, "base");
      e.kind(msg::USER_PUSH);
      e.contact(1);
      e.feature(kFeature);
      e.force(4.0);
      events.write(e);
    }
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
  EXPECT_NEAR(r.peak_force_n(), 7.0, 1e-6) << "the user's force, the tool's weight taken out";
  EXPECT_EQ(r.push_force_n(), 4.0);
  EXPECT_FALSE(registration.take(r)) << "one attachment, one report";
}

TEST(DisplayMetrics, ACameraPoseTurnedByATenthOfADegreeReadsItsPixelsAndTheSummaryHasThem) {
  // The tracked camera pose turned 0.1 deg about the camera's y axis from the true one: the cube's
  // corners are drawn about fx * 0.1 deg = 1.05 px off (exactly: their projections through both).
  const haptics::Scene scene = haptics::load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/scenes/display_demo.yaml");
  const std::string summary = std::string(WYSIWYF_TEST_SCRATCH_DIR) + "/display_metrics_summary.json";
  std::filesystem::create_directories(WYSIWYF_TEST_SCRATCH_DIR);
  std::filesystem::remove(summary);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, summary: " + summary + "}", 1000, &loader);
  auto objects = h.feed<msg::ObjectState>("objects");
  auto tracked = h.feed<msg::PoseStamped>("eye_T_base");
  auto truth = h.feed<msg::PoseStamped>("true_eye_T_base");
  auto info = h.feed<msg::CameraInfo>("camera_info");
  h.activate();
  const std::array<double, 4> K{600, 600, 319.5, 239.5};
  msg::CameraInfo ci;
  ci.width(640), ci.height(480);
  ci.k()[0] = K[0], ci.k()[4] = K[1], ci.k()[2] = K[2], ci.k()[5] = K[3], ci.k()[8] = 1;
  info.write(ci);
  // The demo's camera: at (1.6, -0.35, 0.7) looking at (0.75, 0, 0.15), OpenCV axes.
  const Eigen::Vector3d eye(1.6, -0.35, 0.7), target(0.75, 0.0, 0.15);
  const Eigen::Vector3d z = (target - eye).normalized(), x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  base_T_eye.linear() << x, z.cross(x), z;
  base_T_eye.translation() = eye;
  const Eigen::Isometry3d true_eye_T_base = base_T_eye.inverse();
  const Eigen::Isometry3d drawn_eye_T_base =
      Eigen::Isometry3d(Eigen::AngleAxisd(0.1 * M_PI / 180, Eigen::Vector3d::UnitY())) * true_eye_T_base;
  const int cube = scene.body_index("cube");
  ASSERT_GE(cube, 0);
  Eigen::Isometry3d base_T_cube = Eigen::Isometry3d::Identity();
  base_T_cube.linear() = scene.initial[static_cast<std::size_t>(cube)].q.toRotationMatrix();
  base_T_cube.translation() = scene.initial[static_cast<std::size_t>(cube)].x;
  // The expected figures, from the corners' projections through both poses.
  const Eigen::Vector3d half = scene.models[static_cast<std::size_t>(cube)].half_extents;
  double want_px = 0, want_mm = 0;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p = base_T_cube * Eigen::Vector3d(c & 1 ? half.x() : -half.x(), c & 2 ? half.y() : -half.y(),
                                                            c & 4 ? half.z() : -half.z());
    const Eigen::Vector3d a = drawn_eye_T_base * p, b = true_eye_T_base * p;
    want_mm = std::max(want_mm, (a - b).norm() * 1e3);
    want_px =
        std::max(want_px, std::hypot(K[0] * (a.x() / a.z() - b.x() / b.z()), K[1] * (a.y() / a.z() - b.y() / b.z())));
  }
  EXPECT_NEAR(want_px, 600 * 0.1 * M_PI / 180, 0.1) << "about fx times the angle";
  for (int k = 0; k < 10; ++k) {
    const std::int64_t ns = k * 40 * kMs;
    msg::ObjectState o;
    fill_header(o.header(), ns, static_cast<std::uint64_t>(k), "base");
    o.child_frame_id("cube");
    msgs::to_msg(base_T_cube, o.pose());
    objects.write(o);
    msg::PoseStamped a, b;
    fill_header(a.header(), ns, static_cast<std::uint64_t>(k), "eye");
    fill_header(b.header(), ns, static_cast<std::uint64_t>(k), "eye");
    msgs::to_msg(drawn_eye_T_base, a.pose());
    msgs::to_msg(true_eye_T_base, b.pose());
    tracked.write(a);
    truth.write(b);
    h.tick(Time{ns});
  }
  h.deactivate();
  const YAML::Node j = YAML::LoadFile(summary);  // JSON is YAML
  const YAML::Node v = j["visual_registration"];
  ASSERT_TRUE(v.IsMap()) << summary;
  EXPECT_EQ(v["images"].as<int>(), 10);
  EXPECT_NEAR(v["p50_px"].as<double>(), want_px, 1e-6);
  EXPECT_NEAR(v["max_px"].as<double>(), want_px, 1e-6);
  EXPECT_NEAR(v["p99_mm"].as<double>(), want_mm, 1e-6);
  EXPECT_TRUE(j["contacts"].IsSequence());
  EXPECT_EQ(j["haptic_registration"]["run"]["samples"].as<int>(), 0);
}

TEST(DisplayMetrics, BleedThroughAndLatencyReadTheirKnownAnswers) {
  // A 10 x 10 px device; the compositor shows 9 px inside it, one on its outline (where the
  // image's blur mixes the device with its neighbours: not counted) and 5 off it. Two frames:
  // the second shows nothing of the device. A shown image whose frame has no truth is skipped.
  const std::string summary = std::string(WYSIWYF_TEST_SCRATCH_DIR) + "/display_metrics_bleed.json";
  std::filesystem::create_directories(WYSIWYF_TEST_SCRATCH_DIR);
  std::filesystem::remove(summary);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, summary: " + summary + "}", 1000, &loader);
  auto shown = h.feed<msg::Image>("shown");
  auto device = h.feed<msg::Image>("true_device_mask");
  auto composite = h.feed<msg::Image>("composite");
  h.activate();
  const auto mono = [](std::int64_t stamp) {
    msg::Image m;
    fill_header(m.header(), stamp, 0, "eye");
    m.width(20), m.height(20), m.encoding("mono8"), m.step(20);
    m.data().assign(400, 0);
    return m;
  };
  for (int frame = 0; frame < 3; ++frame) {
    const std::int64_t stamp = (frame + 1) * 40 * kMs;
    msg::Image d = mono(stamp), a = mono(frame == 2 ? stamp + 1 : stamp);
    for (int v = 5; v < 15; ++v)
      for (int u = 5; u < 15; ++u) d.data()[static_cast<std::size_t>(v * 20 + u)] = 255;
    if (frame == 0) {
      for (int v = 7; v < 10; ++v)
        for (int u = 7; u < 10; ++u) a.data()[static_cast<std::size_t>(v * 20 + u)] = 200;
      a.data()[5 * 20 + 5] = 255;                                               // the outline
      for (int u = 0; u < 5; ++u) a.data()[static_cast<std::size_t>(u)] = 255;  // off the device
    }
    // The composite of that frame, made 25 ms after the camera took it (same seq as its alpha).
    a.header().seq(static_cast<std::uint64_t>(frame));
    msg::Image c = mono(stamp + 25 * kMs);
    c.header().seq(static_cast<std::uint64_t>(frame));
    device.write(d);
    composite.write(c);
    shown.write(a);
    h.tick(Time{stamp + 25 * kMs});
  }
  h.deactivate();
  const YAML::Node b = YAML::LoadFile(summary)["bleed_through"];
  ASSERT_TRUE(b.IsMap()) << summary;
  EXPECT_EQ(b["images"].as<int>(), 2) << "the third frame has no truth";
  EXPECT_EQ(b["images_with_any"].as<int>(), 1);
  EXPECT_EQ(b["max_px"].as<double>(), 9.0);
  const YAML::Node l = YAML::LoadFile(summary)["visual_latency"];
  EXPECT_EQ(l["images"].as<int>(), 3);
  EXPECT_NEAR(l["camera_to_composite_p50_ms"].as<double>(), 25.0, 1e-9);
  EXPECT_NEAR(l["camera_to_composite_max_ms"].as<double>(), 25.0, 1e-9);
}

TEST(DisplayMetrics, AForceOnsetThreeFramesAfterTheVisualContactReadsThreeFrames) {
  // 25 frames a second, each composited as it is taken; the finger reaches the surface at 120 ms
  // (the frame taken then shows it), the wrist force passes 1 N only at 240 ms: the user saw the
  // contact 120 ms, three frames, before feeling it.
  const haptics::Scene scene = haptics::load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/scenes/display_demo.yaml");
  const std::string summary = std::string(WYSIWYF_TEST_SCRATCH_DIR) + "/display_metrics_timing.json";
  std::filesystem::create_directories(WYSIWYF_TEST_SCRATCH_DIR);
  std::filesystem::remove(summary);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, summary: " + summary + "}", 1000, &loader);
  auto device = h.feed<msg::PoseStamped>("device_pose");
  auto wrench = h.feed<msg::WrenchStamped>("wrench");
  auto events = h.feed<msg::UserEvent>("events");
  auto shown = h.feed<msg::Image>("shown");
  auto composite = h.feed<msg::Image>("composite");
  h.activate();
  const Eigen::Isometry3d plate = base_T_cube(0) * scene.feature(kFeature)->obj_T_plate;
  const Eigen::Matrix3d base_R_sensor = plate.linear() * scene.device.dev_T_sensor.linear();
  for (int k = 0; k <= 400; ++k) {
    const std::int64_t ns = k * kMs;
    msg::PoseStamped d;
    fill_header(d.header(), ns, static_cast<std::uint64_t>(k), "base");
    msgs::to_msg(plate, d.pose());
    device.write(d);
    const double user = k >= 240 ? 3.0 : 0.0;
    const Eigen::Vector3d weight = base_R_sensor.transpose() * (scene.device.tool_mass * scene.gravity);
    msg::WrenchStamped w;
    fill_header(w.header(), ns, static_cast<std::uint64_t>(k), "ft_sensor");
    msgs::to_msg(Eigen::Vector3d(weight - user * base_R_sensor.transpose() * plate.linear().col(2)),
                 Eigen::Vector3d(scene.device.tool_com.cross(weight)), w.wrench());
    wrench.write(w);
    if (k == 120) {
      msg::UserEvent e;
      fill_header(e.header(), ns, 0, "base");
      e.kind(msg::USER_TOUCH);
      e.contact(1);
      e.feature(kFeature);
      events.write(e);
    }
    if (k % 40 == 0) {  // a frame, composited at once
      msg::Image a, c;
      fill_header(a.header(), ns, static_cast<std::uint64_t>(k), "eye");
      fill_header(c.header(), ns, static_cast<std::uint64_t>(k), "eye");
      a.width(1), a.height(1), a.encoding("mono8"), a.step(1), a.data().assign(1, 0);
      c.width(1), c.height(1), c.encoding("rgb8"), c.step(3), c.data().assign(3, 0);
      composite.write(c);
      shown.write(a);
    }
    h.tick(Time{ns});
  }
  h.deactivate();
  const YAML::Node t = YAML::LoadFile(summary)["contact_timing"];
  ASSERT_TRUE(t.IsSequence() && t.size() == 1) << summary;
  EXPECT_NEAR(t[0]["force_rise_after_touch_ms"].as<double>(), 120.0, 1e-9);
  EXPECT_NEAR(t[0]["seen_after_touch_ms"].as<double>(), 0.0, 1e-9);
  EXPECT_NEAR(t[0]["seen_after_force_frames"].as<double>(), -3.0, 1e-9);
}

TEST(DisplayMetrics, LoopHealthKeepsTheWorstTickAndTheLatestCounts) {
  const std::string summary = std::string(WYSIWYF_TEST_SCRATCH_DIR) + "/display_metrics_health.json";
  std::filesystem::create_directories(WYSIWYF_TEST_SCRATCH_DIR);
  std::filesystem::remove(summary);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, summary: " + summary + "}", 1000, &loader);
  auto diagnostics = h.feed<kernel_msgs::Diagnostics>("diagnostics");
  h.activate();
  // Two one-second windows of a 1 kHz component: p99 40 then 25 us, 3 then 5 samples dropped.
  for (int w = 0; w < 2; ++w) {
    kernel_msgs::Diagnostics d;
    fill_header(d.header(), (w + 1) * 1000 * kMs, static_cast<std::uint64_t>(w), "");
    d.instance("physics"), d.type("admittance_sim");
    d.rate_hz(1000), d.tick_rate_hz(w == 0 ? 998 : 1000);
    d.tick_time_p99_us(w == 0 ? 40 : 25), d.tick_time_max_us(w == 0 ? 90 : 60);
    d.ticks(static_cast<std::uint64_t>(1000 * (w + 1))), d.dropped_samples(w == 0 ? 3 : 5);
    diagnostics.write(d);
    h.tick(Time{(w + 1) * 1000 * kMs});
  }
  h.deactivate();
  const YAML::Node c = YAML::LoadFile(summary)["loop_health"]["physics"];
  ASSERT_TRUE(c.IsMap()) << summary;
  EXPECT_EQ(c["type"].as<std::string>(), "admittance_sim");
  EXPECT_EQ(c["achieved_hz"].as<double>(), 1000.0);
  EXPECT_EQ(c["tick_p99_us"].as<double>(), 40.0) << "the worst window";
  EXPECT_EQ(c["tick_max_us"].as<double>(), 90.0);
  EXPECT_EQ(c["ticks"].as<int>(), 2000);
  EXPECT_EQ(c["dropped"].as<int>(), 5) << "the latest (the counts are cumulative)";
}

TEST(DisplayMetrics, ReadingTheKernelsDiagnosticsIsNotAnUnpublishedTopic) {
  const std::string yaml =
      "wysiwyf: 1\nname: health\nclock: {mode: sim, step: 1ms}\ncomponents:\n"
      "  metrics: {type: display_metrics, rate: 100, params: {scene: scenes/display_demo.yaml},\n"
      "            topics: {diagnostics: wysiwyf/diagnostics}}\n";
  Loader loader({WYSIWYF_COMPONENT_DIR});
  const ValidationResult v = validate_pipeline(load_pipeline_from_string(yaml, "health.yaml"), loader);
  ASSERT_TRUE(v.ok());
  for (const auto& w : v.warnings) EXPECT_EQ(w.str().find("wysiwyf/diagnostics"), std::string::npos) << w.str();
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

// Setpoint to motion: a plate that is where the setpoint was 7 ms earlier reads 7 ms; setpoints
// that command no motion are not timed.
TEST(DisplayMetrics, APlateSevenMillisecondsBehindItsSetpointReadsSevenMilliseconds) {
  const std::string summary = std::string(WYSIWYF_TEST_SCRATCH_DIR) + "/display_metrics_lag.json";
  std::filesystem::create_directories(WYSIWYF_TEST_SCRATCH_DIR);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, summary: " + summary + "}", 1000, &loader);
  auto setpoint = h.feed<msg::CartesianSetpoint>("setpoint");
  auto device = h.feed<msg::PoseStamped>("device_pose");
  h.activate();
  const auto x = [](std::int64_t t) { return t < 300 * kMs ? 0.5 + 0.1 * t * 1e-9 : 0.53; };  // moves, then holds
  for (std::int64_t t = 0; t < 500 * kMs; t += kMs) {
    msg::CartesianSetpoint sp;
    fill_header(sp.header(), t, static_cast<std::uint64_t>(t / kMs), "base");
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x(t), 0.0, 0.2);
    msgs::to_msg(T, sp.pose());
    sp.twist().linear().x(t < 300 * kMs ? 0.1 : 0.0);
    setpoint.write(sp);
    msg::PoseStamped p;
    fill_header(p.header(), t, static_cast<std::uint64_t>(t / kMs), "base");
    T.translation().x() = x(std::max<std::int64_t>(0, t - 7 * kMs));
    msgs::to_msg(T, p.pose());
    device.write(p);
    h.tick(Time{t});
  }
  h.deactivate();
  const YAML::Node m = YAML::LoadFile(summary)["setpoint_to_motion"];
  ASSERT_TRUE(m.IsMap()) << summary;
  EXPECT_EQ(m["setpoints"].as<int>(), 300) << "the 300 moving ones";
  EXPECT_EQ(m["not_reached"].as<int>(), 0);
  EXPECT_NEAR(m["p50_ms"].as<double>(), 7.0, 1e-9);
  EXPECT_NEAR(m["max_ms"].as<double>(), 7.0, 1e-9);
}

// Sensor sample to setpoint. Admittance: a wrench sample every 1 ms and a physics step every
// 20 ms (the paper's) whose setpoints answer the sample of 2 ms before: each waited 2 to 21 ms.
// Surface: a hand sample every 10 ms, first answered 45 ms later and repeated by the setpoints
// between, with no hand input: one figure per answered sample, 45 ms. Holds (sensed_ns 0) are
// not counted and break the run: the first setpoint after one counts only its own sample.
TEST(DisplayMetrics, EverySensorSampleReadsTheWaitForTheFirstSetpointAnsweringIt) {
  const std::string summary = std::string(WYSIWYF_TEST_SCRATCH_DIR) + "/display_metrics_sensed.json";
  std::filesystem::create_directories(WYSIWYF_TEST_SCRATCH_DIR);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, summary: " + summary + "}", 1000, &loader);
  auto setpoint = h.feed<msg::CartesianSetpoint>("setpoint");
  auto wrench = h.feed<msg::WrenchStamped>("wrench");
  h.activate();
  std::int64_t answered = 0;  // admittance: the sample the physics step took
  for (std::int64_t t = 100 * kMs; t < 400 * kMs; t += kMs) {
    const int phase = static_cast<int>(t / (100 * kMs));  // 1: surface, 2: a hold, 3: admittance
    msg::WrenchStamped w;
    fill_header(w.header(), t, 0, "ft_sensor");
    wrench.write(w);
    if (t % (20 * kMs) == 2 * kMs) answered = t - 2 * kMs;  // a step took the sample of 2 ms ago
    msg::CartesianSetpoint sp;
    fill_header(sp.header(), t, static_cast<std::uint64_t>(t / kMs), "base");
    msgs::to_msg(Eigen::Isometry3d::Identity(), sp.pose());
    sp.source(phase == 1 ? "supervisor/surface" : phase == 2 ? "supervisor/hold" : "supervisor/admittance");
    const std::int64_t hand_sample = t - 45 * kMs - (t - 100 * kMs) % (10 * kMs);  // new every 10 ms, 45 ms old
    sp.sensed_ns(phase == 1 ? hand_sample : phase == 2 ? 0 : answered);
    setpoint.write(sp);
    h.tick(Time{t});
  }
  h.deactivate();
  const YAML::Node m = YAML::LoadFile(summary)["sensor_to_setpoint"];
  ASSERT_TRUE(m.IsMap()) << summary;
  EXPECT_EQ(m.size(), 2u) << "wrench and hand; nothing for the hold";
  EXPECT_EQ(m["hand"]["samples"].as<int>(), 10) << "one per hand sample";
  EXPECT_NEAR(m["hand"]["p50_ms"].as<double>(), 45.0, 1e-9);
  EXPECT_NEAR(m["hand"]["max_ms"].as<double>(), 45.0, 1e-9);
  // The first admittance setpoint (t = 300 ms) counts its own sample (280 ms) alone; from then on
  // each step (302, 322, ... 382 ms) answers the 20 samples since the last: 2 .. 21 ms, uniformly.
  EXPECT_EQ(m["wrench"]["samples"].as<int>(), 1 + 5 * 20);
  EXPECT_NEAR(m["wrench"]["max_ms"].as<double>(), 21.0, 1e-9);
  EXPECT_NEAR(m["wrench"]["p50_ms"].as<double>(), 11.0, 1.0);
}

}  // namespace wysiwyf::test
