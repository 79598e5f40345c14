#pragma once
// Lossy image compression for recordings (`wysiwyf record --images video`): a topic's images as
// an H.264 stream (FFmpeg's libavcodec with libx264), one access unit per image in Annex B with
// the parameter sets before every keyframe (a keyframe each kKeyframeInterval images), no
// B-frames, so that each image is one foxglove CompressedVideo message and a reader can start at
// any keyframe. 8-bit images (mono8, rgb8, bgr8) go in as they are (4:2:0 chroma); float depth
// (32FC1) as grey levels: 0 for no depth (NaN, infinite, <= 0), 8-255 for (0, depth_max] metres.
// The decoder gives back images of the recorded encoding and size; its first image must be a
// keyframe, and it refuses a stream whose size is not the channel's before allocating for it.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "image_codec/lossless.hpp"

namespace wysiwyf::io::image_codec {

inline constexpr int kKeyframeInterval = 25;  // 1 s of the simulated cameras

// Whether `image` can go into a video stream ("" if so, else why not: another encoding, an odd
// width or height, rows with padding).
std::string video_problem(const Shape& shape);

class VideoEncoder {
 public:
  // `depth_max`: metres at grey level 255, for 32FC1. Throws std::runtime_error if libavcodec has
  // no libx264 or refuses the settings.
  VideoEncoder(const Shape& shape, float depth_max);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // The access unit of the next image (of the constructor's shape). "" on success.
  std::string encode(const ImageSample& image, std::vector<std::uint8_t>& access_unit, bool& keyframe);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class VideoDecoder {
 public:
  VideoDecoder(const Shape& shape, float depth_max);
  ~VideoDecoder();
  VideoDecoder(const VideoDecoder&) = delete;
  VideoDecoder& operator=(const VideoDecoder&) = delete;

  // The pixels (step x height bytes) of the next access unit. "" on success, else what was wrong
  // (not H.264, another size, a first unit that is no keyframe, corrupt data).
  std::string decode(const std::uint8_t* p, std::size_t n, std::vector<std::uint8_t>& pixels);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wysiwyf::io::image_codec
