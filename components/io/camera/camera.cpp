// camera: a real camera (or a recording) through OpenCV's VideoCapture: a V4L2 device
// ("/dev/video0" or "0"), a video file, or a GStreamer pipeline string. Intrinsics come from an
// OpenCV calibration file (camera_matrix, distortion_coefficients; for a camera of a rectified
// stereo pair also rectification_matrix and projection_matrix); with `undistort` (the default)
// the lens distortion (and the rectifying rotation) is taken out of every frame (one remap
// through maps made once) and camera_info says so (no distortion, K from P): the renderer draws a
// pinhole camera, the filmed hand must lie where the drawn scene does, and a stereo matcher wants
// rows to be epipolar lines. A missing source is an error at
// activation; a source lost while running is reported and reopened, and the pipeline keeps
// running. With `preload`, a file's (or image sequence's) frames are decoded at activation and
// played from memory at the tick rate, stamped when published: a recording as a live camera.
#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "image/image_view.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::io {

class Camera final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("a camera, video file or GStreamer pipeline through OpenCV VideoCapture");
    source_ = ctx.param<std::string>("source", "0", "device index or path, video file, or GStreamer pipeline");
    backend_ = ctx.param_choice("backend", "any", "VideoCapture API", {"any", "v4l2", "ffmpeg", "gstreamer"});
    calibration_ = ctx.param<std::string>(
        "calibration", "",
        "OpenCV calibration YAML (camera_matrix, distortion_coefficients[, rectification_matrix, projection_matrix]); "
        "cwd, then config/");
    at_end_ = ctx.param_choice("at_end", "stop", "when a file ends", {"stop", "loop", "hold"});
    reopen_s_ = ctx.param<double>("reopen_after", 1.0, "seconds without frames before reopening a lost source",
                                  Range{0.05, 60});
    undistort_ = ctx.param<bool>(
        "undistort", true, "take the calibration's lens distortion out of the frames (camera_info then has none)");
    preload_ = ctx.param<bool>("preload", false,
                               "a file source: decode every frame at activation and play them from memory (a recording "
                               "replayed at the tick rate, stamped when published, with no decoding in the tick)");
    image_ = ctx.output<msg::Image>("image", "frames, rgb8", Qos::sensor(2));
    info_ = ctx.output<msg::CameraInfo>("camera_info", "the calibration, with every frame", Qos::sensor(2));
    if (!calibration_.empty()) {
      try {
        load_calibration();
      } catch (const std::exception& e) {
        ctx.reject("calibration", e.what());
      }
    }
  }

  void activate() override {
    if (!open()) throw std::runtime_error("cannot open camera source '" + source_ + "' (backend " + backend_ + ")");
    if (preload_) load_all();
  }

  void tick(Time now) override {
    if (preload_) return play_loaded(now);
    if (!capture_.isOpened()) {
      if (now.ns - lost_since_ns_ > static_cast<std::int64_t>(reopen_s_ * 1e9)) {
        lost_since_ns_ = now.ns;
        if (open()) log("camera source '" + source_ + "' is back");
      }
      return;
    }
    if (!capture_.read(bgr_) || bgr_.empty()) {
      if (is_file_ && at_end_ == "loop" && frames_ > 0) {
        capture_.set(cv::CAP_PROP_POS_FRAMES, 0);
        return;
      }
      if (is_file_ && at_end_ == "stop") {
        request_stop("end of " + source_ + " after " + std::to_string(frames_) + " frames");
        return;
      }
      if (is_file_) return;  // hold: nothing new
      log("lost camera source '" + source_ + "'; reopening every " + std::to_string(reopen_s_) + " s");
      capture_.release();
      lost_since_ns_ = now.ns;
      return;
    }
    to_rgb(vision::image::allocate(msg_, bgr_.cols, bgr_.rows, "rgb8"));
    publish(now);
  }

  void deactivate() override { capture_.release(); }

 private:
  // bgr_ as rgb8 (undistorted when there are maps for its size) into `rgb`.
  void to_rgb(cv::Mat rgb) {
    if (!map1_.empty() && bgr_.size() != map1_.size()) {
      warn_once("size", "frames of " + std::to_string(bgr_.cols) + "x" + std::to_string(bgr_.rows) +
                            " px, but the calibration is for " + std::to_string(map1_.cols) + "x" +
                            std::to_string(map1_.rows) + ": published as they come, not undistorted");
      cv::cvtColor(bgr_, rgb, cv::COLOR_BGR2RGB);
    } else if (!map1_.empty()) {
      cv::remap(bgr_, undistorted_, map1_, map2_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
      cv::cvtColor(undistorted_, rgb, cv::COLOR_BGR2RGB);
    } else {
      cv::cvtColor(bgr_, rgb, cv::COLOR_BGR2RGB);  // straight into the message's buffer
    }
  }

  void publish(Time now) {
    fill_header(msg_.header(), now.ns, frames_++, "eye");
    image_.write(msg_);
    if (!calibration_.empty()) {
      info_msg_.header() = msg_.header();
      info_.write(info_msg_);
    }
  }

  void load_all() {
    if (!is_file_) throw std::runtime_error("preload: source '" + source_ + "' is not a file");
    while (capture_.read(bgr_) && !bgr_.empty()) {
      loaded_.emplace_back(bgr_.rows, bgr_.cols, CV_8UC3);
      to_rgb(loaded_.back());
    }
    capture_.release();
    if (loaded_.empty()) throw std::runtime_error("preload: no frames in '" + source_ + "'");
    log("preloaded " + std::to_string(loaded_.size()) + " frames of " + std::to_string(loaded_[0].cols) + "x" +
        std::to_string(loaded_[0].rows) + " from " + source_);
  }

  void play_loaded(Time now) {
    if (next_ == loaded_.size()) {
      if (at_end_ == "stop") return request_stop("end of " + source_ + " after " + std::to_string(frames_) + " frames");
      if (at_end_ == "hold") return;
      next_ = 0;
    }
    const cv::Mat& f = loaded_[next_++];
    f.copyTo(vision::image::allocate(msg_, f.cols, f.rows, "rgb8"));
    publish(now);
  }

  bool open() {
    const int api = backend_ == "v4l2"        ? cv::CAP_V4L2
                    : backend_ == "ffmpeg"    ? cv::CAP_FFMPEG
                    : backend_ == "gstreamer" ? cv::CAP_GSTREAMER
                                              : cv::CAP_ANY;
    const bool index = !source_.empty() && source_.find_first_not_of("0123456789") == std::string::npos;
    is_file_ = !index && source_.find('!') == std::string::npos && source_.rfind("/dev/", 0) != 0;
    return index ? capture_.open(std::stoi(source_), api) : capture_.open(source_, api);
  }

  // The calibration file: camera_matrix, distortion_coefficients, image_width/height; for one
  // camera of a rectified stereo pair also rectification_matrix (R) and projection_matrix (P, 3x4:
  // the right camera's P[0][3] = -fx B), as cv::stereoRectify gives them.
  void load_calibration() {
    calibration_ = find_config_file(calibration_);  // throws, naming where it looked
    cv::FileStorage fs(calibration_, cv::FileStorage::READ);
    if (!fs.isOpened()) throw std::invalid_argument("calibration: cannot read '" + calibration_ + "'");
    const std::string where = "calibration '" + calibration_ + "'";
    cv::Mat K, D, R, P;
    fs["camera_matrix"] >> K;
    fs["distortion_coefficients"] >> D;
    fs["rectification_matrix"] >> R;
    fs["projection_matrix"] >> P;
    if (K.rows != 3 || K.cols != 3) throw std::invalid_argument(where + ": expected a 3x3 camera_matrix");
    if (!R.empty() && (R.rows != 3 || R.cols != 3))
      throw std::invalid_argument(where + ": expected a 3x3 rectification_matrix");
    if (!P.empty() && (P.rows != 3 || P.cols != 4))
      throw std::invalid_argument(where + ": expected a 3x4 projection_matrix");
    K.convertTo(K, CV_64F);
    if (!D.empty()) D.convertTo(D, CV_64F);
    if (!R.empty()) R.convertTo(R, CV_64F);
    if (!P.empty()) P.convertTo(P, CV_64F);
    info_msg_.width(static_cast<std::uint32_t>(static_cast<int>(fs["image_width"])));
    info_msg_.height(static_cast<std::uint32_t>(static_cast<int>(fs["image_height"])));
    info_msg_.distortion_model("plumb_bob");
    info_msg_.d().clear();
    const bool distorted = !D.empty() && cv::countNonZero(D) > 0;
    const bool rectified = !R.empty() || !P.empty();
    const cv::Mat new_K = P.empty() ? K : P(cv::Rect(0, 0, 3, 3)).clone();
    if (undistort_ && (distorted || rectified)) {
      // Frames are remapped to the pinhole new_K (rotated by R for a rectified pair): camera_info
      // then carries no distortion and no rotation.
      const cv::Size size(static_cast<int>(info_msg_.width()), static_cast<int>(info_msg_.height()));
      if (size.width <= 0 || size.height <= 0)
        throw std::invalid_argument(where + ": expected image_width and image_height");
      cv::initUndistortRectifyMap(K, D.empty() ? cv::Mat() : D, R, new_K, size, CV_16SC2, map1_, map2_);
      info_msg_.d().assign(5, 0.0);
      for (int i = 0; i < 9; ++i) info_msg_.k()[i] = new_K.at<double>(i / 3, i % 3);
      info_msg_.r() = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    } else {
      for (int i = 0; i < static_cast<int>(D.total()) && i < 14; ++i) info_msg_.d().push_back(D.at<double>(i));
      for (int i = 0; i < 9; ++i) info_msg_.k()[i] = K.at<double>(i / 3, i % 3);
      info_msg_.r() = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      if (!R.empty())
        for (int i = 0; i < 9; ++i) info_msg_.r()[i] = R.at<double>(i / 3, i % 3);
    }
    if (!P.empty())
      for (int i = 0; i < 12; ++i) info_msg_.p()[i] = P.at<double>(i / 4, i % 4);
    else
      info_msg_.p() = {
          K.at<double>(0, 0), 0, K.at<double>(0, 2), 0, 0, K.at<double>(1, 1), K.at<double>(1, 2), 0, 0, 0, 1, 0};
  }

  std::string source_, backend_, calibration_, at_end_;
  double reopen_s_ = 1.0;
  bool is_file_ = false, undistort_ = true, preload_ = false;
  std::vector<cv::Mat> loaded_;  // preload: every frame, rgb8
  std::size_t next_ = 0;
  cv::Mat map1_, map2_, undistorted_;  // undistortion maps (empty: frames as they come)
  cv::VideoCapture capture_;
  cv::Mat bgr_;
  std::uint64_t frames_ = 0;
  std::int64_t lost_since_ns_ = 0;
  msg::Image msg_;
  msg::CameraInfo info_msg_;
  Output<msg::Image> image_;
  Output<msg::CameraInfo> info_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::Camera, "camera")
