// libs/io/image_codec, what `wysiwyf record --images lossless` writes and `wysiwyf play` reads:
// every encoding it packs comes back bit for bit (the Image sample's CDR byte for byte); the
// simulated camera's noisy image (camera_sim's own sensor effects) packs under the share that
// keeps the demo's recording under 350 MB; what it cannot pack stays raw; and hostile packed
// messages (corrupt, truncated, empty, claiming another or a huge size, bad metadata) are refused
// with a reason, without a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "image_codec/image_cdr.hpp"
#include "image_codec/lossless.hpp"
#include "image_codec/recorded_image.hpp"
#include "sensor_effects.hpp"

namespace wysiwyf::io::image_codec {
namespace {

std::unique_ptr<VideoDecoder> no_video;  // (the lossless packings use no decoder state)

// A 64x48 image of `encoding` (sizes odd on purpose elsewhere): deterministic pixels, with noise.
ImageSample image(const std::string& encoding, std::uint32_t width = 64, std::uint32_t height = 48) {
  ImageSample im;
  im.stamp_ns = 1'234'567'891'011;
  im.seq = 4'000'000'000u;
  im.frame_id = "camera_optical";
  im.width = width;
  im.height = height;
  im.encoding = encoding;
  const std::uint32_t bpp = encoding == "mono8" ? 1 : encoding == "32FC1" ? 4 : encoding.size() == 5 ? 4 : 3;
  im.step = width * bpp;
  im.data.resize(std::size_t{im.step} * height);
  std::mt19937 rng(7);
  if (encoding == "32FC1") {  // depth: a slanted plane, a step, and the values depth images hold besides
    for (std::uint32_t y = 0; y < height; ++y)
      for (std::uint32_t x = 0; x < width; ++x) {
        float d = 0.8f + 0.001f * x + 0.002f * y + (x > width / 2 ? 0.3f : 0.f);
        if (x == 3) d = std::numeric_limits<float>::quiet_NaN();
        if (x == 4) d = std::numeric_limits<float>::infinity();
        if (x == 5) d = -0.0f;
        if (x == 6) d = static_cast<float>(rng()) * 1e-3f;
        std::memcpy(im.data.data() + y * im.step + 4 * x, &d, 4);
      }
  } else {
    for (std::size_t i = 0; i < im.data.size(); ++i)
      im.data[i] = static_cast<std::uint8_t>(i * 7 / im.step + rng() % 9);
    if (bpp == 4)  // transparent pixels that keep a colour: lossless WebP must keep it too
      for (std::size_t i = 3; i < im.data.size(); i += 8) im.data[i] = 0;
  }
  return im;
}

std::vector<std::uint8_t> packed_message(const ImageSample& im, Metadata& metadata) {
  const Packing packing = lossless_packing(im);
  EXPECT_NE(packing, Packing::kRaw) << im.encoding;
  metadata = packed_metadata(shape_of(im), packing);
  EXPECT_EQ(unpackable(im, shape_of(im), packing), "");
  std::vector<std::uint8_t> cdr;
  EXPECT_EQ(pack(im, packing, cdr), "");
  return cdr;
}

class EveryPackedEncoding : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryPackedEncoding, ComesBackByteForByte) {
  for (auto [w, h] : {std::pair{64u, 48u}, std::pair{17u, 5u}, std::pair{1u, 1u}}) {
    const ImageSample im = image(GetParam(), w, h);
    const std::vector<std::uint8_t> original = image_cdr(im);
    ImageSample parsed;  // the CDR reader and writer agree
    ASSERT_EQ(parse_image(original.data(), original.size(), parsed), "");
    EXPECT_EQ(image_cdr(parsed), original);

    Metadata metadata;
    const auto packed = packed_message(im, metadata);
    CompressedFrame frame;  // the message is a CompressedImage of the same stamp and frame
    ASSERT_EQ(parse_compressed(packed.data(), packed.size(), frame), "");
    EXPECT_EQ(frame.stamp_ns, im.stamp_ns);
    EXPECT_EQ(frame.frame_id, im.frame_id);
    EXPECT_EQ(frame.format, std::string(GetParam()) == "32FC1" ? "png" : "webp");
    std::vector<std::uint8_t> back;
    ASSERT_EQ(unpack(metadata, static_cast<std::uint32_t>(im.seq), packed.data(), packed.size(), back, no_video), "");
    EXPECT_EQ(back, original) << GetParam() << " " << w << "x" << h;
  }
}

INSTANTIATE_TEST_SUITE_P(Encodings, EveryPackedEncoding,
                         ::testing::Values("mono8", "rgb8", "bgr8", "rgba8", "bgra8", "32FC1"));

TEST(ImagePacking, BgrComesOutOfTheWebpInTrueColours) {
  ImageSample im = image("bgr8", 4, 1);
  for (std::size_t i = 0; i < im.data.size(); i += 3)
    im.data[i] = 200, im.data[i + 1] = 10, im.data[i + 2] = 0;  // blue
  Metadata metadata;
  const auto packed = packed_message(im, metadata);
  CompressedFrame frame;
  ASSERT_EQ(parse_compressed(packed.data(), packed.size(), frame), "");
  const cv::Mat decoded = cv::imdecode(frame.data, cv::IMREAD_COLOR);  // OpenCV decodes to BGR
  ASSERT_FALSE(decoded.empty());
  EXPECT_EQ(decoded.at<cv::Vec3b>(0, 0), cv::Vec3b(200, 10, 0));
}

// The demo's camera images: camera_sim's sensor effects (noise sigma 2 grey levels, blur 0.7 px)
// on a rendered scene. Lossless WebP keeps 41.8 % of the demo's images; zstd (the chunks alone)
// 65 %, which put the demo's recording at 533 MB. This bound keeps it under 350 MB.
TEST(ImagePacking, TheSimulatedCamerasNoisyImagePacksUnderHalfItsPixels) {
  cv::Mat scene(480, 640, CV_8UC3, cv::Scalar(90, 110, 130));
  cv::rectangle(scene, {0, 300, 640, 180}, cv::Scalar(60, 80, 120), cv::FILLED);     // a table
  cv::rectangle(scene, {260, 180, 140, 140}, cv::Scalar(40, 160, 220), cv::FILLED);  // a cube
  cv::circle(scene, {150, 200}, 40, cv::Scalar(170, 190, 230), cv::FILLED);          // a hand
  render::SensorEffects effects({2.0, 0.7, 0.3, cv::Scalar(200, 60, 20)}, 1);
  effects.apply(scene, cv::Mat(), 1.0);
  ImageSample im = image("rgb8", 640, 480);
  std::memcpy(im.data.data(), scene.data, im.data.size());
  EXPECT_GT(zstd_share(im), 0.5);  // what the chunks alone would leave (not a lossless codec's job)
  Metadata metadata;
  const auto packed = packed_message(im, metadata);
  EXPECT_LT(static_cast<double>(packed.size()) / static_cast<double>(im.data.size()), 0.45);
  std::vector<std::uint8_t> back;
  ASSERT_EQ(unpack(metadata, static_cast<std::uint32_t>(im.seq), packed.data(), packed.size(), back, no_video), "");
  EXPECT_EQ(back, image_cdr(im));
}

TEST(ImagePacking, WhatCannotBePackedStaysRaw) {
  EXPECT_EQ(lossless_packing(image("mono16")), Packing::kRaw);  // no packing for 16 bits
  ImageSample padded = image("rgb8");
  padded.step += 4, padded.data.resize(std::size_t{padded.step} * padded.height);
  EXPECT_EQ(lossless_packing(padded), Packing::kRaw);  // rows with padding
  ImageSample big_endian = image("32FC1");
  big_endian.is_bigendian = 1;
  EXPECT_EQ(lossless_packing(big_endian), Packing::kRaw);
  ImageSample flat = image("rgb8", 640, 480);
  std::fill(flat.data.begin(), flat.data.end(), 77);
  EXPECT_LT(zstd_share(flat), 0.05);  // a rendered image: the recorder leaves it to the chunks
  const ImageSample im = image("rgb8");
  ImageSample later = im;
  later.stamp_ns = -1;
  EXPECT_NE(unpackable(later, shape_of(im), Packing::kWebp).find("foxglove.Time"), std::string::npos);
  later = im, later.seq = std::uint64_t{1} << 32;
  EXPECT_NE(unpackable(later, shape_of(im), Packing::kWebp).find("32 bits"), std::string::npos);
  later = image("rgb8", 32, 48);
  EXPECT_NE(unpackable(later, shape_of(im), Packing::kWebp).find("shape changed"), std::string::npos);
}

TEST(ImageCdr, RefusesEveryTruncationAndBytesItWouldNotWriteBack) {
  const std::vector<std::uint8_t> cdr = image_cdr(image("rgb8", 5, 3));
  ImageSample out;
  for (std::size_t n = 0; n < cdr.size(); ++n) EXPECT_NE(parse_image(cdr.data(), n, out), "") << n;
  std::vector<std::uint8_t> longer = cdr;
  longer.push_back(0);
  EXPECT_NE(parse_image(longer.data(), longer.size(), out).find("after the last field"), std::string::npos);
  std::vector<std::uint8_t> padding = cdr;  // frame_id "camera_optical": 4 + 15 bytes, then 1 of padding
  padding[4 + 16 + 4 + 15] = 1;
  EXPECT_NE(parse_image(padding.data(), padding.size(), out).find("padding"), std::string::npos);
  std::vector<std::uint8_t> big_endian = cdr;
  big_endian[1] = 0x00;
  EXPECT_NE(parse_image(big_endian.data(), big_endian.size(), out).find("little-endian"), std::string::npos);
}

// Hostile packed messages: each refused with a reason that names what was wrong.
TEST(ImageUnpacking, RefusesCorruptTruncatedEmptyAndOversizedImages) {
  for (const char* encoding : {"rgb8", "32FC1"}) {
    SCOPED_TRACE(encoding);
    const ImageSample im = image(encoding);
    Metadata metadata;
    const auto packed = packed_message(im, metadata);
    CompressedFrame frame;
    ASSERT_EQ(parse_compressed(packed.data(), packed.size(), frame), "");
    std::vector<std::uint8_t> out;
    const auto refused = [&](const CompressedFrame& f, const Metadata& m) {
      const auto cdr = compressed_cdr(f);
      return unpack(m, 1, cdr.data(), cdr.size(), out, no_video);
    };
    CompressedFrame f = frame;
    f.data.clear();  // zero-size
    EXPECT_NE(refused(f, metadata).find("not a"), std::string::npos);
    f = frame, f.data.resize(f.data.size() / 2);  // truncated
    EXPECT_NE(refused(f, metadata), "");
    f = frame;
    std::mt19937 rng(3);
    for (std::size_t i = 40; i < f.data.size(); ++i) f.data[i] = static_cast<std::uint8_t>(rng());  // corrupt
    EXPECT_NE(refused(f, metadata), "");
    f = frame, f.format = f.format == "png" ? "webp" : "png";
    EXPECT_NE(refused(f, metadata).find("format"), std::string::npos);
    Metadata m = metadata;  // the channel claims another size than the image has
    m["image_width"] = "32", m["image_step"] = std::to_string(32 * (std::string(encoding) == "rgb8" ? 3 : 4));
    EXPECT_NE(refused(frame, m).find("recording says"), std::string::npos) << refused(frame, m);
    m = metadata, m["image_width"] = "100000";
    EXPECT_NE(refused(frame, m).find("image_width"), std::string::npos);
    m = metadata, m["image_height"] = "16000", m["image_width"] = "16000";
    m["image_step"] = std::string(encoding) == "rgb8" ? "48000" : "64000";
    EXPECT_NE(refused(frame, m).find("at most"), std::string::npos);  // more pixels than an Image holds
    m = metadata, m["image_step"] = "-1";
    EXPECT_NE(refused(frame, m).find("image_step"), std::string::npos);
    m = metadata, m.erase("image_encoding");
    EXPECT_NE(refused(frame, m).find("image_encoding"), std::string::npos);
    m = metadata, m["image_packing"] = "jpeg";
    EXPECT_NE(refused(frame, m).find("image_packing"), std::string::npos);
    for (std::size_t n = 0; n < packed.size(); n += 7)  // the CompressedImage's CDR cut anywhere
      EXPECT_NE(unpack(metadata, 1, packed.data(), n, out, no_video), "") << n;
  }
}

// A PNG whose header claims a huge image must not make the decoder allocate it.
TEST(ImageUnpacking, RefusesAPngThatClaimsAHugeImageBeforeDecodingIt) {
  const ImageSample im = image("32FC1");
  Metadata metadata;
  const auto packed = packed_message(im, metadata);
  CompressedFrame frame;
  ASSERT_EQ(parse_compressed(packed.data(), packed.size(), frame), "");
  frame.data[16] = 0x7f;  // IHDR width: 2 billion
  const auto cdr = compressed_cdr(frame);
  std::vector<std::uint8_t> out;
  EXPECT_NE(unpack(metadata, 1, cdr.data(), cdr.size(), out, no_video).find("a PNG of"), std::string::npos);
}

}  // namespace
}  // namespace wysiwyf::io::image_codec
