// libs/io/image_codec's video (`wysiwyf record --images video`): a topic's images through H.264
// and back: every image gives one access unit and comes back with its stamp, seq, frame, size
// and encoding, its pixels within a PSNR bound (lossy); keyframes come every kKeyframeInterval
// images with the parameter sets before them; depth comes back within a few grey levels' depth; a
// decoder refuses a stream that starts without a keyframe, empty, corrupt or other-sized units.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "image_codec/image_cdr.hpp"
#include "image_codec/recorded_image.hpp"
#include "image_codec/video.hpp"
#include "sensor_effects.hpp"

namespace wysiwyf::io::image_codec {
namespace {

// Image i of a moving scene seen by the simulated camera (camera_sim's noise and blur).
ImageSample camera_image(int i, render::SensorEffects& effects, const std::string& encoding = "rgb8") {
  cv::Mat scene(240, 320, CV_8UC3, cv::Scalar(90, 110, 130));
  cv::rectangle(scene, {0, 150, 320, 90}, cv::Scalar(60, 80, 120), cv::FILLED);
  cv::rectangle(scene, {100 + 2 * i, 80, 70, 70}, cv::Scalar(40, 160, 220), cv::FILLED);
  effects.apply(scene, cv::Mat(), 1.0);
  if (encoding == "mono8") cv::cvtColor(scene, scene, cv::COLOR_BGR2GRAY);
  ImageSample im;
  im.stamp_ns = 40'000'000LL * i;
  im.seq = static_cast<std::uint64_t>(i);
  im.frame_id = "camera_optical";
  im.width = 320;
  im.height = 240;
  im.encoding = encoding;
  im.step = 320 * static_cast<std::uint32_t>(scene.channels());
  im.data.assign(scene.data, scene.data + scene.total() * scene.elemSize());
  return im;
}

double psnr(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  double se = 0;
  for (std::size_t i = 0; i < a.size(); ++i) se += (a[i] - b[i]) * (a[i] - b[i]);
  return 10 * std::log10(255.0 * 255.0 / std::max(se / static_cast<double>(a.size()), 1e-9));
}

// Whether an access unit holds an IDR slice and, before it, an SPS and a PPS.
bool keyframe_with_parameter_sets(const std::vector<std::uint8_t>& au) {
  bool sps = false, pps = false;
  for (std::size_t i = 0; i + 3 < au.size(); ++i) {
    if (au[i] != 0 || au[i + 1] != 0 || au[i + 2] != 1) continue;
    const int type = au[i + 3] & 0x1f;
    sps |= type == 7, pps |= type == 8;
    if (type == 5) return sps && pps;
  }
  return false;
}

class Video : public ::testing::TestWithParam<const char*> {};

TEST_P(Video, EveryImageComesBackWithItsHeaderAndPixelsWithinAPsnrBound) {
  render::SensorEffects effects({2.0, 0.7, 0.3, cv::Scalar(200, 60, 20)}, 1);
  const Shape shape = shape_of(camera_image(0, effects, GetParam()));
  VideoEncoder encoder(shape, 0);
  const Metadata metadata = packed_metadata(shape, Packing::kH264);
  std::unique_ptr<VideoDecoder> decoder;
  for (int i = 0; i < 60; ++i) {
    const ImageSample im = camera_image(i, effects, GetParam());
    ASSERT_EQ(unpackable(im, shape, Packing::kH264), "");
    std::vector<std::uint8_t> cdr, back;
    ASSERT_EQ(pack_video(im, encoder, cdr), "") << i;
    CompressedFrame frame;
    ASSERT_EQ(parse_compressed(cdr.data(), cdr.size(), frame), "");
    EXPECT_EQ(frame.format, "h264");
    EXPECT_EQ(keyframe_with_parameter_sets(frame.data), i % kKeyframeInterval == 0) << "image " << i;
    ASSERT_EQ(unpack(metadata, static_cast<std::uint32_t>(im.seq), cdr.data(), cdr.size(), back, decoder), "") << i;
    ImageSample out;
    ASSERT_EQ(parse_image(back.data(), back.size(), out), "");
    EXPECT_EQ(out.stamp_ns, im.stamp_ns);
    EXPECT_EQ(out.seq, im.seq);
    EXPECT_EQ(out.frame_id, im.frame_id);
    EXPECT_EQ(shape_of(out).encoding, shape.encoding);
    EXPECT_EQ(out.width, im.width);
    EXPECT_EQ(out.step, im.step);
    ASSERT_EQ(out.data.size(), im.data.size());
    EXPECT_GT(psnr(out.data, im.data), 30.0) << "image " << i;
    EXPECT_LT(frame.data.size(), im.data.size() / 10) << "image " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Encodings, Video, ::testing::Values("rgb8", "bgr8", "mono8"));

TEST(Video, DepthComesBackWithinAFewGreyLevelsAndNoDepthStaysNone) {
  ImageSample im;
  im.width = 64, im.height = 48, im.encoding = "32FC1", im.step = 64 * 4, im.stamp_ns = 5;
  im.data.resize(std::size_t{im.step} * im.height);
  for (std::uint32_t y = 0; y < im.height; ++y)
    for (std::uint32_t x = 0; x < im.width; ++x) {
      const float d = x < 8 ? std::numeric_limits<float>::quiet_NaN() : 0.5f + 0.01f * static_cast<float>(y);
      std::memcpy(im.data.data() + (y * im.width + x) * 4, &d, 4);
    }
  const float depth_max = depth_max_for(im);
  EXPECT_NEAR(depth_max, 1.25f * 0.97f, 1e-5);
  VideoEncoder encoder(shape_of(im), depth_max);
  std::vector<std::uint8_t> cdr, back;
  ASSERT_EQ(pack_video(im, encoder, cdr), "");
  std::unique_ptr<VideoDecoder> decoder;
  ASSERT_EQ(unpack(packed_metadata(shape_of(im), Packing::kH264, depth_max), 0, cdr.data(), cdr.size(), back, decoder),
            "");
  ImageSample out;
  ASSERT_EQ(parse_image(back.data(), back.size(), out), "");
  const double level = depth_max / 247.0;  // (grey levels 8-255)
  double worst = 0, sum = 0;
  int n = 0;
  for (std::uint32_t y = 0; y < im.height; ++y)
    for (std::uint32_t x = 8; x < im.width; ++x) {
      float a, b;
      std::memcpy(&a, im.data.data() + (y * im.width + x) * 4, 4);
      std::memcpy(&b, out.data.data() + (y * im.width + x) * 4, 4);
      sum += std::abs(double{b} - a) / level, ++n;
      if (x >= 12) worst = std::max(worst, std::abs(double{b} - a) / level);  // (not beside the no-depth edge)
    }
  std::printf("depth error in grey levels: mean %.2f, worst %.2f\n", sum / n, worst);
  EXPECT_LT(sum / n, 1.5);  // (crf 28 is lossy on the grey levels themselves)
  EXPECT_LT(worst, 6.0);
  float none;
  std::memcpy(&none, out.data.data() + (10 * im.width + 2) * 4, 4);
  EXPECT_TRUE(std::isnan(none));
}

TEST(Video, TheDecoderRefusesAStreamWithoutAKeyframeAndEmptyCorruptOrOtherSizedUnits) {
  render::SensorEffects effects({2.0, 0.7, 0.3, cv::Scalar(200, 60, 20)}, 1);
  const Shape shape = shape_of(camera_image(0, effects));
  VideoEncoder encoder(shape, 0);
  std::vector<std::vector<std::uint8_t>> units(3);
  bool keyframe = false;
  for (int i = 0; i < 3; ++i) ASSERT_EQ(encoder.encode(camera_image(i, effects), units[i], keyframe), "");
  std::vector<std::uint8_t> pixels;
  {
    VideoDecoder decoder(shape, 0);
    EXPECT_NE(decoder.decode(units[1].data(), units[1].size(), pixels).find("keyframe"), std::string::npos);
    EXPECT_NE(decoder.decode(units[0].data(), 0, pixels).find("empty"), std::string::npos);
    std::vector<std::uint8_t> noise(5000);
    for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<std::uint8_t>(i * 131 + 7);
    EXPECT_NE(decoder.decode(noise.data(), noise.size(), pixels), "");
    EXPECT_EQ(decoder.decode(units[0].data(), units[0].size(), pixels), "");  // and a good stream still decodes
    EXPECT_EQ(decoder.decode(units[1].data(), units[1].size(), pixels), "");
  }
  {
    Shape larger = shape;  // the channel says 640x480; the stream is 320x240
    larger.width = 640, larger.height = 480, larger.step = 640 * 3;
    VideoDecoder decoder(larger, 0);
    EXPECT_NE(decoder.decode(units[0].data(), units[0].size(), pixels).find("recording says"), std::string::npos);
    Shape smaller = shape;  // the stream claims more pixels than the channel: refused before allocating
    smaller.width = 160, smaller.height = 120, smaller.step = 160 * 3;
    VideoDecoder small(smaller, 0);
    EXPECT_NE(small.decode(units[0].data(), units[0].size(), pixels), "");
  }
  EXPECT_NE(video_problem({241, 320, 960, "rgb8", 0}), "");    // odd height
  EXPECT_NE(video_problem({240, 320, 1280, "rgba8", 0}), "");  // alpha does not go into a video
}

}  // namespace
}  // namespace wysiwyf::io::image_codec
