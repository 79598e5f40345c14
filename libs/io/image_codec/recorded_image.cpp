#include "image_codec/recorded_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace wysiwyf::io::image_codec {

namespace {

constexpr std::int64_t kMaxStampNs = (std::int64_t{1} << 32) * 1'000'000'000 - 1;  // foxglove.Time's uint32 seconds

// A metadata value as an unsigned number up to `max`; false if absent or not one.
bool number(const Metadata& m, const char* key, std::uint64_t max, std::uint64_t& out, std::string& why) {
  const auto it = m.find(key);
  if (it == m.end()) return why = std::string("channel metadata has no ") + key, false;
  const std::string& v = it->second;
  if (v.empty() || v.size() > 10 || v.find_first_not_of("0123456789") != std::string::npos || std::stoull(v) > max)
    return why =
               std::string("channel metadata ") + key + " = '" + v + "'; expected a number 0 to " + std::to_string(max),
           false;
  out = std::stoull(v);
  return true;
}

}  // namespace

Metadata packed_metadata(const Shape& shape, Packing packing, float depth_max) {
  Metadata m = {
      {"image_packing", packing_name(packing)},     {"image_encoding", shape.encoding},
      {"image_width", std::to_string(shape.width)}, {"image_height", std::to_string(shape.height)},
      {"image_step", std::to_string(shape.step)},   {"image_is_bigendian", std::to_string(shape.is_bigendian)}};
  if (packing == Packing::kH264 && shape.encoding == "32FC1") {
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", static_cast<double>(depth_max));
    m["image_depth_max"] = text;
  }
  return m;
}

bool is_packed(const Metadata& metadata) { return metadata.count("image_packing") > 0; }

std::string unpackable(const ImageSample& image, const Shape& shape, Packing packing) {
  const Shape s = shape_of(image);
  if (s.encoding != shape.encoding || s.width != shape.width || s.height != shape.height || s.step != shape.step ||
      s.is_bigendian != shape.is_bigendian)
    return "the image's shape changed (now " + s.encoding + " " + std::to_string(s.width) + "x" +
           std::to_string(s.height) + ")";
  if (packing == Packing::kH264 ? !video_problem(s).empty() : lossless_packing(image) != packing)
    return "the image cannot be packed as " + packing_name(packing);
  if (image.data.size() != std::size_t{s.step} * s.height)
    return std::to_string(image.data.size()) + " bytes of pixels; expected step x height";
  if (image.stamp_ns < 0 || image.stamp_ns > kMaxStampNs)
    return "stamp " + std::to_string(image.stamp_ns) + " ns is outside foxglove.Time (0 to 2^32 s)";
  if (image.seq > std::numeric_limits<std::uint32_t>::max())
    return "header.seq " + std::to_string(image.seq) + " does not fit the MCAP sequence (32 bits)";
  return "";
}

std::string pack(const ImageSample& image, Packing packing, std::vector<std::uint8_t>& cdr) {
  CompressedFrame frame;
  frame.stamp_ns = image.stamp_ns;
  frame.frame_id = image.frame_id;
  if (auto why = encode_lossless(image, packing, frame); !why.empty()) return why;
  cdr = compressed_cdr(frame);
  return "";
}

std::string pack_video(const ImageSample& image, VideoEncoder& encoder, std::vector<std::uint8_t>& cdr) {
  CompressedFrame frame;
  frame.stamp_ns = image.stamp_ns;
  frame.frame_id = image.frame_id;
  frame.format = "h264";
  bool keyframe = false;
  if (auto why = encoder.encode(image, frame.data, keyframe); !why.empty()) return why;
  cdr = compressed_cdr(frame);
  return "";
}

float depth_max_for(const ImageSample& image) {
  float farthest = 0;
  for (std::size_t i = 0; i + 4 <= image.data.size(); i += 4) {
    float d;
    std::memcpy(&d, image.data.data() + i, 4);
    if (std::isfinite(d)) farthest = std::max(farthest, d);
  }
  return std::max(0.01f, 1.25f * farthest);
}

std::string unpack(const Metadata& metadata, std::uint32_t sequence, const std::uint8_t* p, std::size_t n,
                   std::vector<std::uint8_t>& out, std::unique_ptr<VideoDecoder>& video) {
  Packing packing = Packing::kRaw;
  const auto packing_it = metadata.find("image_packing");
  if (packing_it == metadata.end() || !parse_packing(packing_it->second, packing) || packing == Packing::kRaw)
    return "channel metadata image_packing = '" + (packing_it == metadata.end() ? "" : packing_it->second) +
           "'; expected webp, float32-delta-planes-png or h264";
  std::string why;
  std::uint64_t width = 0, height = 0, step = 0, bigendian = 0;
  if (!number(metadata, "image_width", 16384, width, why) || !number(metadata, "image_height", 16384, height, why) ||
      !number(metadata, "image_step", kMaxImageBytes, step, why) ||
      !number(metadata, "image_is_bigendian", 1, bigendian, why))
    return why;
  const auto encoding = metadata.find("image_encoding");
  if (encoding == metadata.end()) return "channel metadata has no image_encoding";
  CompressedFrame frame;
  if (auto problem = parse_compressed(p, n, frame); !problem.empty()) return problem;
  ImageSample image;
  image.stamp_ns = frame.stamp_ns;
  image.seq = sequence;
  image.frame_id = frame.frame_id;
  image.width = static_cast<std::uint32_t>(width);
  image.height = static_cast<std::uint32_t>(height);
  image.step = static_cast<std::uint32_t>(step);
  image.encoding = encoding->second;
  image.is_bigendian = static_cast<std::uint8_t>(bigendian);
  const std::string expected = packing == Packing::kWebp ? "webp" : packing == Packing::kH264 ? "h264" : "png";
  if (frame.format != expected)
    return "format '" + frame.format + "'; the channel's packing " + packing_name(packing) + " is " + expected;
  if (packing == Packing::kH264) {
    if (!video) {
      if (auto why = video_problem(shape_of(image)); !why.empty()) return why;
      float depth_max = 0;
      if (image.encoding == "32FC1") {
        const auto it = metadata.find("image_depth_max");
        if (it == metadata.end() || !(std::strtof(it->second.c_str(), nullptr) > 0))
          return "channel metadata image_depth_max = '" + (it == metadata.end() ? "" : it->second) +
                 "'; expected a depth in metres > 0";
        depth_max = std::strtof(it->second.c_str(), nullptr);
      }
      try {
        video = std::make_unique<VideoDecoder>(shape_of(image), depth_max);
      } catch (const std::exception& e) {
        return e.what();
      }
    }
    if (auto problem = video->decode(frame.data.data(), frame.data.size(), image.data); !problem.empty())
      return problem;
  } else if (auto problem = decode_lossless(frame.data.data(), frame.data.size(), packing, shape_of(image), image.data);
             !problem.empty())
    return problem;
  out = image_cdr(image);
  return "";
}

}  // namespace wysiwyf::io::image_codec
