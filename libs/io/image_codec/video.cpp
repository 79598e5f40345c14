#include "image_codec/video.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace wysiwyf::io::image_codec {

namespace {

// x264's constant rate factor: 28 keeps the noisy camera images recognisable at ~15 kB each
// (PSNR ~35 dB; docs/performance.md, Recording).
constexpr const char* kCrf = "28";
constexpr std::size_t kMaxAccessUnit = std::size_t{16} << 20;
// Depth as grey: 0 for no depth, kFirstDepthLevel-255 for (0, depth_max] metres. The gap keeps
// "no depth" apart from the nearest depth after the codec's error (a few levels at edges).
constexpr int kFirstDepthLevel = 8;
constexpr double kDepthLevels = 255 - kFirstDepthLevel;

AVPixelFormat pixel_format(const std::string& encoding) {
  if (encoding == "rgb8") return AV_PIX_FMT_RGB24;
  if (encoding == "bgr8") return AV_PIX_FMT_BGR24;
  return AV_PIX_FMT_GRAY8;  // mono8, and 32FC1 as grey levels
}

std::string av_error(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof(text));
  return text;
}

// Whether an Annex B access unit holds an IDR slice (NAL type 5): where a decoder may start.
bool has_idr(const std::uint8_t* p, std::size_t n) {
  for (std::size_t i = 0; i + 3 < n; ++i)
    if (p[i] == 0 && p[i + 1] == 0 && p[i + 2] == 1 && (p[i + 3] & 0x1f) == 5) return true;
  return false;
}

// What an encoder and a decoder hold alike: libavcodec's and libswscale's state, the stream's
// shape, and the grey levels of a depth image.
struct Stream {
  Shape shape;
  float depth_max = 0;
  AVCodecContext* ctx = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  std::vector<std::uint8_t> grey;
  ~Stream() {
    sws_freeContext(sws);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&ctx);
  }
};

}  // namespace

std::string video_problem(const Shape& s) {
  if (s.encoding != "rgb8" && s.encoding != "bgr8" && s.encoding != "mono8" &&
      !(s.encoding == "32FC1" && !s.is_bigendian))
    return "encoding '" + s.encoding + "' does not go into a video (rgb8, bgr8, mono8, 32FC1 do)";
  if (s.width < 16 || s.height < 16 || s.width % 2 || s.height % 2 || s.width > 4096 || s.height > 4096)
    return "size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
           "; a video needs even sizes, 16 to 4096";
  const std::uint32_t bpp = s.encoding == "32FC1" ? 4 : s.encoding == "mono8" ? 1 : 3;
  if (s.step != s.width * bpp)
    return "step " + std::to_string(s.step) + "; expected width x " + std::to_string(bpp) + " (rows without padding)";
  return "";
}

struct VideoEncoder::Impl : Stream {
  std::int64_t pts = 0;
};

VideoEncoder::VideoEncoder(const Shape& shape, float depth_max) : impl_(std::make_unique<Impl>()) {
  if (auto why = video_problem(shape); !why.empty()) throw std::runtime_error(why);
  Impl& m = *impl_;
  m.shape = shape;
  m.depth_max = depth_max;
  av_log_set_level(AV_LOG_ERROR);  // (libx264 would print its settings for each topic)
  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (!codec) throw std::runtime_error("libavcodec has no libx264 encoder (Debian's libavcodec is built with it)");
  m.ctx = avcodec_alloc_context3(codec);
  m.ctx->width = static_cast<int>(shape.width);
  m.ctx->height = static_cast<int>(shape.height);
  m.ctx->pix_fmt = AV_PIX_FMT_YUV420P;
  m.ctx->time_base = {1, 25};
  m.ctx->framerate = {25, 1};
  m.ctx->gop_size = kKeyframeInterval;
  m.ctx->max_b_frames = 0;  // each image out as it goes in
  m.ctx->thread_count = 1;  // (the recorder's writer thread; frame threads would delay the output)
  av_opt_set(m.ctx->priv_data, "preset", "veryfast", 0);
  av_opt_set(m.ctx->priv_data, "tune", "zerolatency", 0);
  av_opt_set(m.ctx->priv_data, "crf", kCrf, 0);
  // SPS and PPS before every keyframe, keyframes only every gop_size images (not at scene cuts).
  av_opt_set(m.ctx->priv_data, "x264-params", "repeat-headers=1:scenecut=0", 0);
  if (const int r = avcodec_open2(m.ctx, codec, nullptr); r < 0)
    throw std::runtime_error("libx264 refused the settings: " + av_error(r));
  m.frame = av_frame_alloc();
  m.frame->format = AV_PIX_FMT_YUV420P;
  m.frame->width = m.ctx->width;
  m.frame->height = m.ctx->height;
  if (av_frame_get_buffer(m.frame, 0) < 0) throw std::runtime_error("out of memory for a video frame");
  m.packet = av_packet_alloc();
  m.sws = sws_getContext(m.ctx->width, m.ctx->height, pixel_format(shape.encoding), m.ctx->width, m.ctx->height,
                         AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr, nullptr, nullptr);
  if (!m.sws) throw std::runtime_error("libswscale cannot convert " + shape.encoding + " to YUV 4:2:0");
}

VideoEncoder::~VideoEncoder() = default;

std::string VideoEncoder::encode(const ImageSample& image, std::vector<std::uint8_t>& access_unit, bool& keyframe) {
  Impl& m = *impl_;
  const std::uint8_t* source = image.data.data();
  int stride = static_cast<int>(image.step);
  if (image.encoding == "32FC1") {  // depth to grey levels
    m.grey.resize(std::size_t{image.width} * image.height);
    for (std::size_t i = 0; i < m.grey.size(); ++i) {
      float d;
      std::memcpy(&d, image.data.data() + 4 * i, 4);
      m.grey[i] = std::isfinite(d) && d > 0
                      ? static_cast<std::uint8_t>(kFirstDepthLevel +
                                                  std::lround(kDepthLevels * std::min(d, m.depth_max) / m.depth_max))
                      : 0;
    }
    source = m.grey.data();
    stride = static_cast<int>(image.width);
  }
  if (av_frame_make_writable(m.frame) < 0) return "out of memory for a video frame";
  sws_scale(m.sws, &source, &stride, 0, static_cast<int>(image.height), m.frame->data, m.frame->linesize);
  m.frame->pts = m.pts++;
  if (const int r = avcodec_send_frame(m.ctx, m.frame); r < 0) return "libx264 refused an image: " + av_error(r);
  const int r = avcodec_receive_packet(m.ctx, m.packet);
  if (r == AVERROR(EAGAIN)) return "libx264 held an image back (no access unit for it)";
  if (r < 0) return "libx264 failed: " + av_error(r);
  access_unit.assign(m.packet->data, m.packet->data + m.packet->size);
  keyframe = (m.packet->flags & AV_PKT_FLAG_KEY) != 0;
  av_packet_unref(m.packet);
  return "";
}

struct VideoDecoder::Impl : Stream {
  bool started = false;
};

VideoDecoder::VideoDecoder(const Shape& shape, float depth_max) : impl_(std::make_unique<Impl>()) {
  if (auto why = video_problem(shape); !why.empty()) throw std::runtime_error(why);
  Impl& m = *impl_;
  m.shape = shape;
  m.depth_max = depth_max;
  const AVCodec* codec = avcodec_find_decoder(AV_CODEC_ID_H264);
  if (!codec) throw std::runtime_error("libavcodec has no H.264 decoder");
  m.ctx = avcodec_alloc_context3(codec);
  m.ctx->thread_count = 1;  // an image out for each access unit in, without delay
  m.ctx->flags |= AV_CODEC_FLAG_LOW_DELAY;
  m.ctx->max_pixels = std::int64_t{shape.width} * shape.height;  // a stream claiming more is refused
  if (const int r = avcodec_open2(m.ctx, codec, nullptr); r < 0)
    throw std::runtime_error("libavcodec's H.264 decoder: " + av_error(r));
  m.frame = av_frame_alloc();
  m.packet = av_packet_alloc();
}

VideoDecoder::~VideoDecoder() = default;

std::string VideoDecoder::decode(const std::uint8_t* p, std::size_t n, std::vector<std::uint8_t>& pixels) {
  Impl& m = *impl_;
  if (n == 0) return "an empty access unit";
  if (n > kMaxAccessUnit)
    return "an access unit of " + std::to_string(n) + " bytes; at most " + std::to_string(kMaxAccessUnit);
  if (!m.started && !has_idr(p, n)) return "the stream does not start with a keyframe (no IDR slice)";
  if (av_new_packet(m.packet, static_cast<int>(n)) < 0) return "out of memory for an access unit";
  std::memcpy(m.packet->data, p, n);
  const int sent = avcodec_send_packet(m.ctx, m.packet);
  av_packet_unref(m.packet);
  if (sent < 0) return "corrupt H.264 data: " + av_error(sent);
  const int r = avcodec_receive_frame(m.ctx, m.frame);
  if (r == AVERROR(EAGAIN)) return "no image decoded from this access unit";
  if (r < 0) return "corrupt H.264 data: " + av_error(r);
  m.started = true;
  const int w = static_cast<int>(m.shape.width), h = static_cast<int>(m.shape.height);
  if (m.frame->width != w || m.frame->height != h) {
    const std::string why = "a video image of " + std::to_string(m.frame->width) + "x" +
                            std::to_string(m.frame->height) + "; the recording says " + std::to_string(w) + "x" +
                            std::to_string(h);
    av_frame_unref(m.frame);
    return why;
  }
  const bool depth = m.shape.encoding == "32FC1";
  m.sws = sws_getCachedContext(m.sws, w, h, static_cast<AVPixelFormat>(m.frame->format), w, h,
                               pixel_format(m.shape.encoding), SWS_BILINEAR, nullptr, nullptr, nullptr);
  if (!m.sws) {
    av_frame_unref(m.frame);
    return "libswscale cannot convert the decoded images to " + m.shape.encoding;
  }
  pixels.resize(std::size_t{m.shape.step} * m.shape.height);
  if (depth) m.grey.resize(std::size_t{m.shape.width} * m.shape.height);
  std::uint8_t* target = depth ? m.grey.data() : pixels.data();
  const int stride = depth ? w : static_cast<int>(m.shape.step);
  sws_scale(m.sws, m.frame->data, m.frame->linesize, 0, h, &target, &stride);
  av_frame_unref(m.frame);
  if (depth)
    for (std::size_t i = 0; i < m.grey.size(); ++i) {
      const int g = m.grey[i];
      const float d =
          g < kFirstDepthLevel / 2
              ? std::numeric_limits<float>::quiet_NaN()
              : static_cast<float>(std::max(g - kFirstDepthLevel, 0) * static_cast<double>(m.depth_max) / kDepthLevels);
      std::memcpy(pixels.data() + 4 * i, &d, 4);
    }
  return "";
}

}  // namespace wysiwyf::io::image_codec
