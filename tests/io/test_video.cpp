// video_sink writes an MP4; the camera component reads it back through OpenCV's decoding path.
#include <gtest/gtest.h>

#include <filesystem>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

TEST(Video, AnMp4WrittenByVideoSinkReadsBackThroughTheCamera) {
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / "video";
  std::filesystem::remove_all(dir);
  const std::string file = (dir / "clip.mp4").string();
  {
    Harness sink("video_sink", "{path: " + file + ", fps: 25}", 25);
    auto in = sink.feed<msg::Image>("image");
    sink.activate();
    msg::Image f;
    f.width(320), f.height(240), f.encoding("rgb8"), f.step(320 * 3);
    for (int i = 0; i < 12; ++i) {
      f.data().assign(320 * 240 * 3, static_cast<std::uint8_t>(20 * i));  // each frame a different grey
      in.write(f);
      sink.tick(Time{i * 40'000'000LL});
    }
    sink.deactivate();
  }
  ASSERT_TRUE(std::filesystem::exists(file));
  Harness cam("camera", "{source: " + file + ", backend: ffmpeg, at_end: stop}", 25);
  auto out = cam.watch<msg::Image>("image");
  cam.activate();
  std::vector<double> means;
  msg::Image f;
  for (int i = 0; i < 100 && cam.stop_request().empty(); ++i) {
    cam.tick(Time{i * 40'000'000LL});
    while (out.take(f)) {
      ASSERT_EQ(f.width(), 320u);
      ASSERT_EQ(f.height(), 240u);
      double sum = 0;
      for (auto b : f.data()) sum += b;
      means.push_back(sum / static_cast<double>(f.data().size()));
    }
  }
  EXPECT_EQ(means.size(), 12u);
  EXPECT_NE(cam.stop_request().find("end of"), std::string::npos) << cam.stop_request();
  // The frames come back in order: each one near its grey (MPEG-4 through YUV 4:2:0 is lossy, a few levels).
  for (std::size_t i = 0; i < means.size(); ++i) EXPECT_NEAR(means[i], 20.0 * i, 6.0) << "frame " << i;
}

TEST(Video, AMissingCameraSourceIsAClearErrorAtActivation) {
  Harness cam("camera", "{source: /nonexistent/clip.mp4}", 25);
  try {
    cam.activate();
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open camera source '/nonexistent/clip.mp4'"), std::string::npos)
        << e.what();
  }
}

}  // namespace wysiwyf::test

namespace wysiwyf::test {

TEST(Display, WithoutADisplayItSaysSoAndKeepsRunning) {
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  Harness d("display", "{}", 30);
  auto in = d.feed<msg::Image>("image");
  d.activate();
  msg::Image f;
  f.width(4), f.height(4), f.encoding("rgb8"), f.step(12);
  f.data().assign(48, 100);
  for (int i = 0; i < 3; ++i) {
    in.write(f);
    d.tick(Time{i * 33'000'000LL});
  }
  EXPECT_EQ(in.written(), 3u);
  EXPECT_TRUE(d.stop_request().empty());
}

}  // namespace wysiwyf::test
