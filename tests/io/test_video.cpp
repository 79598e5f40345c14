// video_sink writes an MP4 that browsers play (H.264 in the boxes); the camera component reads it
// back through OpenCV's decoding path.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

namespace {

// 12 frames of 320x240, each a different grey, written by video_sink at 25 fps into DIR/clip.mp4.
std::string write_clip(const std::string& dir_name) {
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / dir_name;
  std::filesystem::remove_all(dir);
  const std::string file = (dir / "clip.mp4").string();
  Harness sink("video_sink", "{path: " + file + ", fps: 25}", 25);
  auto in = sink.feed<msg::Image>("image");
  sink.activate();
  msg::Image f;
  f.width(320), f.height(240), f.encoding("rgb8"), f.step(320 * 3);
  for (int i = 0; i < 12; ++i) {
    f.data().assign(320 * 240 * 3, static_cast<std::uint8_t>(20 * i));
    in.write(f);
    sink.tick(Time{i * 40'000'000LL});
  }
  sink.deactivate();
  return file;
}

std::uint32_t be32(std::string_view s, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<std::uint8_t>(s.at(at + i));
  return v;
}

// The payload of the first ISO BMFF box of type TYPE among the boxes that fill DATA (an MP4 file,
// or the payload of a container box); empty if there is none.
std::string_view box(std::string_view data, std::string_view type) {
  std::size_t at = 0;
  while (at + 8 <= data.size()) {
    std::uint64_t size = be32(data, at), header = 8;
    if (size == 1) size = (std::uint64_t{be32(data, at + 8)} << 32 | be32(data, at + 12)), header = 16;
    if (size == 0) size = data.size() - at;  // the last box, to the end of the file
    if (size < header || at + size > data.size()) return {};
    if (data.substr(at + 4, 4) == type) return data.substr(at + header, size - header);
    at += size;
  }
  return {};
}

}  // namespace

// The report's video plays in a browser: Chromium and Firefox decode H.264 in MP4 (8-bit 4:2:0,
// Baseline, Main or High profile) and not MPEG-4 Part 2 ('mp4v'). Read from the file's boxes:
// moov/trak/mdia/minf/stbl/stsd holds the track's sample entry, 'avc1' with its avcC record.
TEST(Video, TheSinksMp4IsH264ThatBrowsersDecode) {
  const std::string file = write_clip("codec");
  std::ifstream in(file, std::ios::binary);
  const std::string mp4{std::istreambuf_iterator<char>(in), {}};
  ASSERT_GT(mp4.size(), 8u);
  EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  std::string_view stbl = mp4;
  for (const char* type : {"moov", "trak", "mdia", "minf", "stbl"}) {
    stbl = box(stbl, type);
    ASSERT_FALSE(stbl.empty()) << "no " << type << " box on the way to stsd";
  }
  const std::string_view stsd = box(stbl, "stsd");
  ASSERT_GE(stsd.size(), 16u);
  EXPECT_EQ(be32(stsd, 4), 1u) << "one sample entry";
  const std::string_view entry_type = stsd.substr(12, 4);
  ASSERT_EQ(entry_type, "avc1") << "the video is '" << entry_type << "', which browsers do not play";
  // A VisualSampleEntry: 78 bytes of fields (width and height at 24 and 26), then its boxes.
  const std::string_view entry = box(stsd.substr(8), "avc1");
  ASSERT_GT(entry.size(), 78u);
  EXPECT_EQ(be32(entry, 24), 320u << 16 | 240u);
  const std::string_view avcc = box(entry.substr(78), "avcC");
  ASSERT_GE(avcc.size(), 7u);
  EXPECT_EQ(avcc[0], 1) << "avcC version";
  const int profile = static_cast<std::uint8_t>(avcc[1]);
  EXPECT_TRUE(profile == 66 || profile == 77 || profile == 100) << "profile_idc " << profile;
  if (profile == 100) {  // High: after the SPS and PPS, the chroma format and the bit depths
    std::size_t at = 6;
    for (int sps = avcc[5] & 31; sps > 0; --sps)
      at += 2 + (std::uint8_t(avcc.at(at)) << 8 | std::uint8_t(avcc.at(at + 1)));
    for (int pps = std::uint8_t(avcc.at(at++)); pps > 0; --pps)
      at += 2 + (std::uint8_t(avcc.at(at)) << 8 | std::uint8_t(avcc.at(at + 1)));
    ASSERT_GE(avcc.size(), at + 3) << "a High profile avcC without its chroma format";
    EXPECT_EQ(avcc[at] & 3, 1) << "chroma_format_idc: 4:2:0 (yuv420p)";
    EXPECT_EQ(avcc[at + 1] & 7, 0) << "8-bit luma";
    EXPECT_EQ(avcc[at + 2] & 7, 0) << "8-bit chroma";
  }
}

TEST(Video, AnMp4WrittenByVideoSinkReadsBackThroughTheCamera) {
  const std::string file = write_clip("video");
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
  // The frames come back in order: each one near its grey (H.264 through YUV 4:2:0 is lossy, a few levels).
  for (std::size_t i = 0; i < means.size(); ++i) EXPECT_NEAR(means[i], 20.0 * i, 6.0) << "frame " << i;
}

// A calibrated camera with lens distortion publishes undistorted frames and says so: a dot filmed
// where the lens puts the undistorted point (290, 215) px comes out there, and camera_info has
// the calibration's K and no distortion.
TEST(Video, TheCameraTakesTheLensDistortionOut) {
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / "undistort";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const cv::Matx33d K(300, 0, 159.5, 0, 300, 119.5, 0, 0, 1);
  const std::vector<double> D{-0.4, 0.1, 0.001, -0.002, 0};
  {
    cv::FileStorage fs((dir / "calibration.yaml").string(), cv::FileStorage::WRITE);
    fs << "image_width" << 320 << "image_height" << 240 << "camera_matrix" << cv::Mat(K) << "distortion_coefficients"
       << cv::Mat(D).t();
  }
  // Where the lens images the ray of the undistorted pixel (290, 215).
  const cv::Point3d ray((290 - K(0, 2)) / K(0, 0), (215 - K(1, 2)) / K(1, 1), 1);
  std::vector<cv::Point2d> seen;
  cv::projectPoints(std::vector<cv::Point3d>{ray}, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, seen);
  cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::circle(frame,
             cv::Point(static_cast<int>(std::lround(seen[0].x * 16)), static_cast<int>(std::lround(seen[0].y * 16))),
             3 * 16, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA, 4);
  for (int i = 0; i < 3; ++i) cv::imwrite((dir / ("frame_" + std::to_string(i) + ".png")).string(), frame);
  Harness cam(
      "camera",
      "{source: " + (dir / "frame_%d.png").string() + ", calibration: " + (dir / "calibration.yaml").string() + "}",
      25);
  auto out = cam.watch<msg::Image>("image");
  auto info = cam.watch<msg::CameraInfo>("camera_info");
  cam.activate();
  cam.tick(Time{0});
  msg::Image f;
  msg::CameraInfo ci;
  ASSERT_TRUE(out.take_latest(f));
  ASSERT_TRUE(info.take_latest(ci));
  EXPECT_DOUBLE_EQ(ci.k()[0], 300);
  EXPECT_DOUBLE_EQ(ci.k()[2], 159.5);
  for (double d : ci.d()) EXPECT_EQ(d, 0.0);
  const cv::Mat rgb(static_cast<int>(f.height()), static_cast<int>(f.width()), CV_8UC3, f.data().data());
  cv::Mat grey;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  const cv::Moments m = cv::moments(grey);
  ASSERT_GT(m.m00, 0);
  EXPECT_NEAR(m.m10 / m.m00, 290, 0.5);
  EXPECT_NEAR(m.m01 / m.m00, 215, 0.5);
  EXPECT_GT(std::hypot(seen[0].x - 290, seen[0].y - 215), 10) << "the lens must move the dot for this to test anything";
}

// The right camera of a rectified stereo pair (cv::stereoRectify's R and P): camera_info carries
// P, whose P[0][3] = -fx B gives stereo readers the baseline, and K = P's left 3x3.
TEST(Video, TheRightCameraOfARectifiedPairGivesItsBaseline) {
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / "rectified";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    cv::FileStorage fs((dir / "right.yaml").string(), cv::FileStorage::WRITE);
    fs << "image_width" << 320 << "image_height" << 240 << "camera_matrix"
       << cv::Mat(cv::Matx33d(302, 0, 161, 0, 301, 118, 0, 0, 1)) << "distortion_coefficients"
       << cv::Mat(std::vector<double>{0.01, 0, 0, 0, 0}).t() << "rectification_matrix" << cv::Mat(cv::Matx33d::eye())
       << "projection_matrix" << cv::Mat(cv::Matx34d(300, 0, 160, -300 * 0.06, 0, 300, 120, 0, 0, 0, 1, 0));
  }
  cv::imwrite((dir / "frame_0.png").string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar(30, 60, 90)));
  Harness cam("camera",
              "{source: " + (dir / "frame_%d.png").string() + ", calibration: " + (dir / "right.yaml").string() + "}",
              25);
  auto info = cam.watch<msg::CameraInfo>("camera_info");
  cam.activate();
  cam.tick(Time{0});
  msg::CameraInfo ci;
  ASSERT_TRUE(info.take_latest(ci));
  EXPECT_DOUBLE_EQ(-ci.p()[3] / ci.p()[0], 0.06);
  EXPECT_DOUBLE_EQ(ci.k()[0], 300);
  EXPECT_DOUBLE_EQ(ci.k()[2], 160);
  for (double d : ci.d()) EXPECT_EQ(d, 0.0);
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

// preload: a recording's frames decoded at activation, played from memory in order at the
// tick rate (looping), each stamped when it is published.
TEST(Video, APreloadedRecordingPlaysItsFramesInOrderAndLoops) {
  const std::filesystem::path dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / "preload";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (int i = 0; i < 3; ++i)
    cv::imwrite((dir / ("f_" + std::to_string(i) + ".png")).string(),
                cv::Mat(8, 10, CV_8UC3, cv::Scalar(10 * i, 20 + i, 200 - i)));  // BGR
  Harness cam("camera", "{source: " + (dir / "f_%d.png").string() + ", preload: true, at_end: loop}", 90);
  auto image = cam.watch<msg::Image>("image");
  cam.activate();
  std::filesystem::remove_all(dir);  // played from memory from now on
  for (int tick = 0; tick < 5; ++tick) {
    const std::int64_t t = 1'000'000'000 + tick * 11'111'111;
    cam.tick(Time{t});
    msg::Image frame;
    ASSERT_TRUE(image.take(frame)) << tick;
    EXPECT_EQ(frame.header().stamp_ns(), t);
    EXPECT_EQ(frame.header().seq(), static_cast<std::uint64_t>(tick));
    ASSERT_EQ(frame.width(), 10u);
    ASSERT_EQ(frame.encoding(), "rgb8");
    const int i = tick % 3;  // frames 0, 1, 2, 0, 1
    EXPECT_EQ((std::vector<int>{frame.data()[0], frame.data()[1], frame.data()[2]}),
              (std::vector<int>{200 - i, 20 + i, 10 * i}))
        << tick;
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
