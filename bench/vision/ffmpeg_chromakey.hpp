#pragma once
// FFmpeg's chromakey filter (Debian's libavfilter), the vision benchmark's peer for the chroma
// keyer: a filter graph buffer -> [scale to yuva444p ->] chromakey -> buffersink on one thread.
// The conversion is FFmpeg's own swscale, to full-range YUV: chromakey turns its RGB key colour
// into U, V with the full-range BT.601 formula, so the frame and the key meet in one colour space.
#include <opencv2/core.hpp>

#include <string>

struct AVFilterGraph;
struct AVFilterContext;
struct AVFrame;

namespace wysiwyf::vision {

class FfmpegChromakey {
 public:
  // chromakey_args: the filter's options, e.g. "color=0x1A299E:similarity=0.06:blend=0.05".
  // with_conversion: the graph takes rgb24 frames and converts them; else it takes yuva444p
  // frames (from to_yuva444p) and times the filter alone.
  FfmpegChromakey(int width, int height, const std::string& chromakey_args, bool with_conversion);
  ~FfmpegChromakey();
  FfmpegChromakey(const FfmpegChromakey&) = delete;
  FfmpegChromakey& operator=(const FfmpegChromakey&) = delete;

  // with_conversion: rgb is CV_8UC3 RGB; alpha (CV_8UC1, 255 = kept) is the filter's alpha plane.
  void key_rgb(const cv::Mat& rgb, cv::Mat& alpha);
  // Without conversion: frame comes from to_yuva444p; chromakey writes its alpha plane in place.
  void key_yuva(AVFrame*& frame, cv::Mat& alpha);

  // The rgb24 image as FFmpeg converts it for chromakey (full-range yuva444p); av_frame_free it.
  static AVFrame* to_yuva444p(const cv::Mat& rgb);

 private:
  void run(AVFrame* in, AVFrame*& out, cv::Mat& alpha);

  AVFilterGraph* graph_ = nullptr;
  AVFilterContext* source_ = nullptr;
  AVFilterContext* sink_ = nullptr;
  AVFrame* input_ = nullptr;
  AVFrame* output_ = nullptr;
  int width_, height_;
  bool with_conversion_;
  long long pts_ = 0;
};

}  // namespace wysiwyf::vision
