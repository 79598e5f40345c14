// The compositor on hand-made images: premultiplied alpha, and z-keying.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::render {

msg::Image image(int w, int h, const char* encoding, int channels_bytes) {
  msg::Image m;
  m.width(w), m.height(h), m.encoding(encoding), m.step(static_cast<std::uint32_t>(w * channels_bytes));
  m.data().assign(static_cast<std::size_t>(w) * h * channels_bytes, 0);
  return m;
}
void set_depth(msg::Image& d, int u, int v, float z) {
  std::memcpy(&d.data()[(static_cast<std::size_t>(v) * d.width() + u) * 4], &z, 4);
}

TEST(Compositor, BlendsThePremultipliedHandOverTheScene) {
  Harness h("compositor", "{}", 60);
  auto scene = h.feed<msg::Image>("scene");
  auto hand = h.feed<msg::Image>("hand");
  auto out = h.watch<msg::Image>("composite");
  h.activate();
  msg::Image s = image(3, 1, "rgb8", 3), k = image(3, 1, "rgba8", 4);
  for (int u = 0; u < 3; ++u) s.data()[u * 3] = 100, s.data()[u * 3 + 1] = 150, s.data()[u * 3 + 2] = 200;
  // Pixel 0: no hand. Pixel 1: opaque hand (10, 20, 30). Pixel 2: half-transparent skin, premultiplied.
  const std::uint8_t hand_px[3][4] = {{0, 0, 0, 0}, {10, 20, 30, 255}, {100, 60, 40, 128}};
  std::memcpy(k.data().data(), hand_px, 12);
  scene.write(s);
  hand.write(k);
  h.tick(Time{0});
  msg::Image c;
  ASSERT_TRUE(out.take_latest(c));
  ASSERT_EQ(c.data().size(), 9u);
  const std::uint8_t* p = c.data().data();
  EXPECT_EQ((std::vector<int>{p[0], p[1], p[2]}), (std::vector<int>{100, 150, 200}));
  EXPECT_EQ((std::vector<int>{p[3], p[4], p[5]}), (std::vector<int>{10, 20, 30}));
  for (int ch = 0; ch < 3; ++ch) {
    const int expected = hand_px[2][ch] + static_cast<int>(std::lround(s.data()[6 + ch] * (255 - 128) / 255.0));
    EXPECT_NEAR(p[6 + ch], expected, 1) << ch;
  }
}

TEST(Compositor, ZKeyingHidesTheHandBehindTheVirtualObject) {
  Harness h("compositor", "{}", 60);
  auto scene = h.feed<msg::Image>("scene");
  auto scene_depth = h.feed<msg::Image>("scene_depth");
  auto hand = h.feed<msg::Image>("hand");
  auto real_depth = h.feed<msg::Image>("real_depth");
  auto out = h.watch<msg::Image>("composite");
  h.activate();
  msg::Image s = image(3, 1, "rgb8", 3), sd = image(3, 1, "32FC1", 4), k = image(3, 1, "rgba8", 4),
             rd = image(3, 1, "32FC1", 4);
  for (int u = 0; u < 3; ++u) {
    s.data()[u * 3] = 200;                                 // the virtual object: red
    k.data()[u * 4 + 1] = 255, k.data()[u * 4 + 3] = 255;  // the hand: opaque green
    set_depth(rd, u, 0, 0.5f);                             // the hand is 0.5 m away
  }
  set_depth(sd, 0, 0, 0.4f);  // the virtual surface in front of the hand: the hand is hidden
  set_depth(sd, 1, 0, 0.6f);  // behind the hand: the hand shows
  set_depth(sd, 2, 0, 0.0f);  // no virtual surface: the hand shows
  scene.write(s), scene_depth.write(sd), hand.write(k), real_depth.write(rd);
  h.tick(Time{0});
  msg::Image c;
  ASSERT_TRUE(out.take_latest(c));
  const std::uint8_t* p = c.data().data();
  EXPECT_EQ((std::vector<int>{p[0], p[1], p[2]}), (std::vector<int>{200, 0, 0}));
  EXPECT_EQ((std::vector<int>{p[3], p[4], p[5]}), (std::vector<int>{0, 255, 0}));
  EXPECT_EQ((std::vector<int>{p[6], p[7], p[8]}), (std::vector<int>{0, 255, 0}));
}

TEST(Compositor, AZMarginKeepsRealThingsLyingOnTheVirtualSurfaceBehindIt) {
  // The hand 3 mm in front of the virtual surface (stereo noise on the plate lying on the cube's
  // face): shown without a margin, hidden with 5 mm; 2 cm in front (a finger): shown with both.
  for (double margin : {0.0, 0.005}) {
    Harness h("compositor", "{z_margin: " + std::to_string(margin) + "}", 60);
    auto scene = h.feed<msg::Image>("scene");
    auto scene_depth = h.feed<msg::Image>("scene_depth");
    auto hand = h.feed<msg::Image>("hand");
    auto real_depth = h.feed<msg::Image>("real_depth");
    auto out = h.watch<msg::Image>("composite");
    h.activate();
    msg::Image s = image(2, 1, "rgb8", 3), sd = image(2, 1, "32FC1", 4), k = image(2, 1, "rgba8", 4),
               rd = image(2, 1, "32FC1", 4);
    for (int u = 0; u < 2; ++u) {
      s.data()[u * 3] = 200;
      k.data()[u * 4 + 1] = 255, k.data()[u * 4 + 3] = 255;
      set_depth(sd, u, 0, 0.6f);
    }
    set_depth(rd, 0, 0, 0.597f);
    set_depth(rd, 1, 0, 0.58f);
    scene.write(s), scene_depth.write(sd), hand.write(k), real_depth.write(rd);
    h.tick(Time{0});
    msg::Image c;
    ASSERT_TRUE(out.take_latest(c));
    const std::uint8_t* p = c.data().data();
    EXPECT_EQ(p[1], margin > 0 ? 0 : 255) << "margin " << margin;
    EXPECT_EQ(p[4], 255) << "margin " << margin;
  }
}

TEST(Compositor, TheDeviceIsKeptOutAndOnlyAHandInFrontOfItShows) {
  // Keyed pixels over no virtual surface, in a repeating pattern of four (37 wide: the vector
  // path and the scalar tail): the device 0.6 m away on the first three, the real depth there
  // 0.55 m (a hand 5 cm in front: shown), 0.59 m (the device itself, 1 cm of stereo noise:
  // hidden with a 3 cm device_margin), unknown (hidden); the fourth is off the device (shown).
  // Without a real depth stream every device pixel is hidden. With z-keying on or off alike.
  constexpr int kWidth = 37;
  for (bool with_depth : {true, false})
    for (bool virtual_depth : {true, false}) {
      Harness h("compositor", "{device_margin: 0.03}", 60);
      auto scene = h.feed<msg::Image>("scene");
      auto scene_depth = h.feed<msg::Image>("scene_depth");
      auto hand = h.feed<msg::Image>("hand");
      auto real_depth = h.feed<msg::Image>("real_depth");
      auto device = h.feed<msg::Image>("device_depth");
      auto out = h.watch<msg::Image>("composite");
      h.activate();
      msg::Image s = image(kWidth, 1, "rgb8", 3), sd = image(kWidth, 1, "32FC1", 4), k = image(kWidth, 1, "rgba8", 4),
                 rd = image(kWidth, 1, "32FC1", 4), dd = image(kWidth, 1, "32FC1", 4);
      for (int u = 0; u < kWidth; ++u) {
        s.data()[u * 3] = 200;
        k.data()[u * 4 + 1] = 255, k.data()[u * 4 + 3] = 255;
        if (u % 4 < 3) set_depth(dd, u, 0, 0.6f);
        if (u % 4 == 0) set_depth(rd, u, 0, 0.55f);
        if (u % 4 == 1) set_depth(rd, u, 0, 0.59f);
        if (u % 4 == 3) set_depth(rd, u, 0, 0.8f);
      }
      scene.write(s), hand.write(k), device.write(dd);
      if (virtual_depth) scene_depth.write(sd);
      if (with_depth) real_depth.write(rd);
      h.tick(Time{0});
      msg::Image c;
      ASSERT_TRUE(out.take_latest(c));
      const std::uint8_t* p = c.data().data();
      for (int u = 0; u < kWidth; ++u) {
        const bool shown = u % 4 == 3 || (u % 4 == 0 && with_depth);
        EXPECT_EQ(p[3 * u + 1], shown ? 255 : 0) << "pixel " << u << (with_depth ? " with" : " without") << " depth";
        EXPECT_EQ(p[3 * u], shown ? 0 : 200) << "pixel " << u;
      }
    }
}

TEST(Compositor, EveryPixelOfAWideImageIsTheRoundedBlend) {
  // 37 x 5 random pixels (the vectorised body, 16 at a time, and the scalar tail), alpha only and
  // z-keyed: each output channel is hand + round(scene (255 - alpha) / 255), with the hand and
  // alpha zeroed where the virtual surface is nearer.
  const int w = 37, h = 5;
  std::uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u, static_cast<int>(state >> 24); };
  msg::Image s = image(w, h, "rgb8", 3), k = image(w, h, "rgba8", 4), sd = image(w, h, "32FC1", 4),
             rd = image(w, h, "32FC1", 4);
  for (auto& b : s.data()) b = static_cast<std::uint8_t>(next());
  for (int i = 0; i < w * h; ++i) {
    const int a = next();
    k.data()[4 * i + 3] = static_cast<std::uint8_t>(a);
    for (int c = 0; c < 3; ++c) k.data()[4 * i + c] = static_cast<std::uint8_t>(next() * a / 255);  // premultiplied
    set_depth(sd, i % w, i / w, (next() % 3) * 0.3f);  // 0 (none), 0.3 or 0.6 m
    set_depth(rd, i % w, i / w, (next() % 3) * 0.3f);
  }
  for (bool z : {false, true}) {
    Harness hs("compositor", "{}", 60);
    auto scene = hs.feed<msg::Image>("scene");
    auto scene_depth = hs.feed<msg::Image>("scene_depth");
    auto hand = hs.feed<msg::Image>("hand");
    auto real_depth = hs.feed<msg::Image>("real_depth");
    auto out = hs.watch<msg::Image>("composite");
    hs.activate();
    scene.write(s), hand.write(k);
    if (z) scene_depth.write(sd), real_depth.write(rd);
    hs.tick(Time{0});
    msg::Image c;
    ASSERT_TRUE(out.take_latest(c));
    for (int i = 0; i < w * h; ++i) {
      float vz, rz;
      std::memcpy(&vz, &sd.data()[4 * static_cast<std::size_t>(i)], 4);
      std::memcpy(&rz, &rd.data()[4 * static_cast<std::size_t>(i)], 4);
      const bool hidden = z && vz > 0 && rz > 0 && vz < rz;
      const int a = hidden ? 0 : k.data()[4 * i + 3];
      for (int ch = 0; ch < 3; ++ch) {
        const int expected = (hidden ? 0 : k.data()[4 * i + ch]) +
                             static_cast<int>(std::lround(s.data()[3 * i + ch] * (255 - a) / 255.0));
        ASSERT_EQ(c.data()[3 * i + ch], std::min(expected, 255)) << "pixel " << i << " channel " << ch << " z " << z;
      }
    }
  }
}

TEST(Compositor, AMalformedImageIsIgnored) {
  Harness h("compositor", "{}", 60);
  auto scene = h.feed<msg::Image>("scene");
  auto out = h.watch<msg::Image>("composite");
  h.activate();
  msg::Image s = image(4, 4, "rgb8", 3);
  s.data().resize(10);  // shorter than height * step
  scene.write(s);
  h.tick(Time{0});
  EXPECT_EQ(out.received(), 0u);
}

}  // namespace wysiwyf::render

namespace wysiwyf::render {

TEST(Compositor, TakesTheHandFromACameraImageAndAMask) {
  Harness h("compositor", "{}", 60);
  auto scene = h.feed<msg::Image>("scene");
  auto camera = h.feed<msg::Image>("camera");
  auto mask = h.feed<msg::Image>("hand_mask");
  auto out = h.watch<msg::Image>("composite");
  h.activate();
  msg::Image s = image(2, 1, "rgb8", 3), c = image(2, 1, "rgb8", 3), m = image(2, 1, "mono8", 1);
  for (int u = 0; u < 2; ++u) s.data()[u * 3 + 2] = 200, c.data()[u * 3] = 180;  // blue scene, red camera
  m.data()[1] = 255;                                                             // the hand is pixel 1
  scene.write(s), camera.write(c), mask.write(m);
  h.tick(Time{0});
  msg::Image r;
  ASSERT_TRUE(out.take_latest(r));
  const std::uint8_t* p = r.data().data();
  EXPECT_EQ((std::vector<int>{p[0], p[1], p[2]}), (std::vector<int>{0, 0, 200}));
  EXPECT_EQ((std::vector<int>{p[3], p[4], p[5]}), (std::vector<int>{180, 0, 0}));
}

// match_frames (data-triggered chains): only layers of one camera frame go together; a hand
// that came ahead of its frame's scene is kept until the scene comes.
TEST(Compositor, MatchFramesCompositesOnlyLayersOfOneCameraFrame) {
  Harness h("compositor", "{match_frames: true, publish_shown: true}", 90);
  auto scene = h.feed<msg::Image>("scene");
  auto hand = h.feed<msg::Image>("hand");
  auto out = h.watch<msg::Image>("composite");
  auto shown = h.watch<msg::Image>("shown");
  h.activate();
  msg::Image s = image(2, 1, "rgb8", 3), k = image(2, 1, "rgba8", 4);
  auto stamped = [](msg::Image m, std::int64_t stamp) {
    m.header().stamp_ns(stamp);
    return m;
  };
  scene.write(stamped(s, 100));
  hand.write(stamped(k, 200));  // the next frame's hand: not this scene's
  h.tick(Time{1});
  msg::Image c;
  EXPECT_FALSE(out.take(c)) << "scene of frame 100 with the hand of frame 200";
  hand.write(stamped(k, 300));  // the keyer runs ahead: two hands wait for their scenes
  h.tick(Time{2});
  EXPECT_FALSE(out.take(c));
  scene.write(stamped(s, 200));
  h.tick(Time{3});
  ASSERT_TRUE(shown.take(c)) << "frame 200's scene finds frame 200's hand in the history";
  EXPECT_EQ(c.header().stamp_ns(), 200);
  scene.write(stamped(s, 300));
  h.tick(Time{4});
  ASSERT_TRUE(shown.take(c));
  EXPECT_EQ(c.header().stamp_ns(), 300);
  h.tick(Time{5});  // nothing new: no second composite of frame 300
  EXPECT_FALSE(shown.take(c));
  EXPECT_EQ(out.pending(), 2u);
}

}  // namespace wysiwyf::render
