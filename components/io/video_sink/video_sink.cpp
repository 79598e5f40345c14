// video_sink: writes an image stream to an MP4 file (H.264, OpenCV's FFmpeg backend) or to numbered
// PNG frames, at the frame rate of the stream.
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "image/image_view.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::io {

class VideoSink final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("writes images to an MP4 file or to PNG frames");
    path_ = ctx.param<std::string>("path", "out/video.mp4", "the MP4 file, or the folder for PNG frames");
    format_ = ctx.param_choice("format", "mp4", "container", {"mp4", "png"});
    fps_ = ctx.param<double>("fps", 30.0, "frame rate written into the MP4", Range{1, 240});
    in_ = ctx.input<msg::Image>("image", "frames, rgb8 or bgr8", Qos::reliable(8));
  }

  void activate() override {
    namespace fs = std::filesystem;
    const fs::path dir = format_ == "png" ? fs::path(path_) : fs::path(path_).parent_path();
    if (!dir.empty()) fs::create_directories(dir);
  }

  void tick(Time) override {
    while (in_.take(frame_)) {
      if (const std::string bad = vision::image::problem(frame_, {"rgb8", "bgr8"}); !bad.empty()) {
        reject(in_, bad);
        continue;
      }
      const cv::Mat view = vision::image::view(frame_);
      if (std::string_view(frame_.encoding().c_str()) == "rgb8")
        cv::cvtColor(view, bgr_, cv::COLOR_RGB2BGR);
      else
        view.copyTo(bgr_);
      write(bgr_);
    }
  }

  void deactivate() override {
    writer_.release();
    log("wrote " + std::to_string(written_) + " frames to " + path_);
  }

 private:
  void write(const cv::Mat& bgr) {
    if (format_ == "png") {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%06llu.png", static_cast<unsigned long long>(written_));
      if (!cv::imwrite((std::filesystem::path(path_) / name).string(), bgr))
        throw std::runtime_error("cannot write PNG frames into " + path_);
    } else {
      if (!writer_.isOpened()) open(bgr.size());
      if (bgr.size() != size_) {  // a video has one frame size
        reject(in_, "a frame of another size than the first (" + std::to_string(size_.width) + "x" +
                        std::to_string(size_.height) + ")");
        return;
      }
      writer_.write(bgr);
    }
    ++written_;
  }

  // H.264 ('avc1': FFmpeg's libx264, High profile, yuv420p, which OpenCV asks of every lossy codec)
  // is what browsers decode, so the run report's video plays in its page; MPEG-4 Part 2 ('mp4v')
  // is kept as a fallback for an FFmpeg built without an H.264 encoder, which browsers do not play.
  void open(cv::Size size) {
    size_ = size;
    if (writer_.open(path_, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('a', 'v', 'c', '1'), fps_, size_)) return;
    if (!writer_.open(path_, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps_, size_))
      throw std::runtime_error("cannot open " + path_ + " for writing with OpenCV's FFmpeg backend");
    warn_once("mp4v", "FFmpeg has no H.264 encoder here: " + path_ + " is MPEG-4 Part 2, which browsers do not play");
  }

  std::string path_, format_;
  double fps_ = 30;
  cv::VideoWriter writer_;
  cv::Size size_;
  cv::Mat bgr_;
  std::uint64_t written_ = 0;
  msg::Image frame_;
  Input<msg::Image> in_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::VideoSink, "video_sink")
