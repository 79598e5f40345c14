#include "ffmpeg_chromakey.hpp"

extern "C" {
#include <libavfilter/avfilter.h>
#include <libavfilter/buffersink.h>
#include <libavfilter/buffersrc.h>
#include <libavutil/frame.h>
#include <libavutil/opt.h>
}

#include <algorithm>
#include <stdexcept>

namespace wysiwyf::vision {

namespace {

void check(int status, const std::string& what) {
  if (status >= 0) return;
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(status, text, sizeof text);
  throw std::runtime_error("libavfilter: " + what + ": " + text);
}

// buffer (in_format) -> chain -> buffersink (yuva444p), on one thread.
AVFilterGraph* build_graph(int width, int height, AVPixelFormat in_format, const std::string& chain,
                           AVFilterContext*& source, AVFilterContext*& sink) {
  AVFilterGraph* graph = avfilter_graph_alloc();
  if (!graph) throw std::runtime_error("libavfilter: cannot allocate a filter graph");
  graph->nb_threads = 1;
  graph->thread_type = 0;  // no slice threads: FFmpeg on one core, as the comparison asks
  const std::string args = "video_size=" + std::to_string(width) + "x" + std::to_string(height) +
                           ":pix_fmt=" + std::to_string(in_format) + ":time_base=1/25:pixel_aspect=1/1";
  try {
    check(avfilter_graph_create_filter(&source, avfilter_get_by_name("buffer"), "in", args.c_str(), nullptr, graph),
          "buffer source");
    check(avfilter_graph_create_filter(&sink, avfilter_get_by_name("buffersink"), "out", nullptr, nullptr, graph),
          "buffer sink");
    const AVPixelFormat formats[] = {AV_PIX_FMT_YUVA444P, AV_PIX_FMT_NONE};
    check(av_opt_set_int_list(sink, "pix_fmts", formats, AV_PIX_FMT_NONE, AV_OPT_SEARCH_CHILDREN), "sink format");
    AVFilterInOut* outputs = avfilter_inout_alloc();
    AVFilterInOut* inputs = avfilter_inout_alloc();
    outputs->name = av_strdup("in"), outputs->filter_ctx = source, outputs->pad_idx = 0, outputs->next = nullptr;
    inputs->name = av_strdup("out"), inputs->filter_ctx = sink, inputs->pad_idx = 0, inputs->next = nullptr;
    const int parsed = avfilter_graph_parse_ptr(graph, chain.c_str(), &inputs, &outputs, nullptr);
    avfilter_inout_free(&inputs);
    avfilter_inout_free(&outputs);
    check(parsed, "filter chain '" + chain + "'");
    check(avfilter_graph_config(graph, nullptr), "graph configuration");
  } catch (...) {
    avfilter_graph_free(&graph);
    throw;
  }
  return graph;
}

const char* kToFullRangeYuva = "scale=out_range=full,format=yuva444p";

}  // namespace

FfmpegChromakey::FfmpegChromakey(int width, int height, const std::string& chromakey_args, bool with_conversion)
    : width_(width), height_(height), with_conversion_(with_conversion) {
  const std::string chain =
      (with_conversion ? std::string(kToFullRangeYuva) + "," : "") + "chromakey=" + chromakey_args;
  graph_ = build_graph(width, height, with_conversion ? AV_PIX_FMT_RGB24 : AV_PIX_FMT_YUVA444P, chain, source_, sink_);
  input_ = av_frame_alloc();
  output_ = av_frame_alloc();
}

FfmpegChromakey::~FfmpegChromakey() {
  av_frame_free(&input_);
  av_frame_free(&output_);
  avfilter_graph_free(&graph_);
}

void FfmpegChromakey::run(AVFrame* in, AVFrame*& out, cv::Mat& alpha) {
  in->pts = pts_++;
  check(av_buffersrc_add_frame_flags(source_, in, 0), "sending a frame");  // hands the frame's reference over
  av_frame_unref(out);
  check(av_buffersink_get_frame(sink_, out), "receiving the keyed frame");
  alpha = cv::Mat(height_, width_, CV_8UC1, out->data[3], static_cast<std::size_t>(out->linesize[3]));
}

void FfmpegChromakey::key_rgb(const cv::Mat& rgb, cv::Mat& alpha) {
  if (!with_conversion_ || rgb.type() != CV_8UC3 || rgb.cols != width_ || rgb.rows != height_)
    throw std::invalid_argument("key_rgb: expected a graph with conversion and a " + std::to_string(width_) + "x" +
                                std::to_string(height_) + " CV_8UC3 image");
  // The image itself, read-only, as the frame's buffer: no copy on the way in.
  input_->format = AV_PIX_FMT_RGB24, input_->width = width_, input_->height = height_;
  input_->buf[0] = av_buffer_create(
      rgb.data, rgb.step * static_cast<std::size_t>(rgb.rows), [](void*, uint8_t*) {}, nullptr,
      AV_BUFFER_FLAG_READONLY);
  input_->data[0] = rgb.data;
  input_->linesize[0] = static_cast<int>(rgb.step);
  run(input_, output_, alpha);
}

void FfmpegChromakey::key_yuva(AVFrame*& frame, cv::Mat& alpha) {
  if (with_conversion_) throw std::invalid_argument("key_yuva: this graph takes rgb24 frames");
  // chromakey keys in place: the frame comes back with its alpha plane written.
  run(frame, frame, alpha);
}

AVFrame* FfmpegChromakey::to_yuva444p(const cv::Mat& rgb) {
  AVFilterContext *source = nullptr, *sink = nullptr;
  AVFilterGraph* graph = build_graph(rgb.cols, rgb.rows, AV_PIX_FMT_RGB24, kToFullRangeYuva, source, sink);
  AVFrame* in = av_frame_alloc();
  in->format = AV_PIX_FMT_RGB24, in->width = rgb.cols, in->height = rgb.rows;
  check(av_frame_get_buffer(in, 0), "allocating a frame");
  for (int y = 0; y < rgb.rows; ++y) std::copy_n(rgb.ptr(y), rgb.cols * 3, in->data[0] + y * in->linesize[0]);
  AVFrame* converted = av_frame_alloc();
  check(av_buffersrc_add_frame_flags(source, in, 0), "sending a frame to convert");
  check(av_buffersink_get_frame(sink, converted), "receiving the converted frame");
  // A copy of our own: writable, whatever pool the conversion's buffer came from.
  AVFrame* out = av_frame_alloc();
  out->format = converted->format, out->width = converted->width, out->height = converted->height;
  check(av_frame_get_buffer(out, 0), "allocating a frame");
  check(av_frame_copy(out, converted), "copying a frame");
  check(av_frame_copy_props(out, converted), "copying frame properties");
  av_frame_free(&in);
  av_frame_free(&converted);
  avfilter_graph_free(&graph);
  return out;
}

}  // namespace wysiwyf::vision
