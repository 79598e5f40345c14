// display: shows an image stream in a window (OpenCV HighGUI) when a display exists. Without
// one (no DISPLAY or WAYLAND_DISPLAY, as on a headless machine) it says so once at activation
// and then only drains its input: the pipeline runs on.
#include <cstdlib>
#include <opencv2/highgui.hpp>
#include <opencv2/imgproc.hpp>

#include "image/image_view.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::io {

class Display final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("shows images in a window when a display exists (headless: a message, no crash)");
    title_ = ctx.param<std::string>("title", "WYSIWYF", "window title");
    in_ = ctx.input<msg::Image>("image", "frames, rgb8", Qos::sensor(2));
  }

  void activate() override {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    headless_ = (!x11 || !*x11) && (!wayland || !*wayland);
    if (headless_) {
      log("no display (DISPLAY and WAYLAND_DISPLAY are unset): frames are not shown; use video_sink to record them");
      return;
    }
    try {
      cv::namedWindow(title_, cv::WINDOW_AUTOSIZE);
    } catch (const cv::Exception& e) {
      headless_ = true;
      log(std::string("cannot open a window (") + e.what() + "): frames are not shown");
    }
  }

  void tick(Time) override {
    if (!in_.take_latest(frame_) || headless_) return;
    if (const std::string bad = vision::image::problem(frame_, {"rgb8"}); !bad.empty()) return reject(in_, bad);
    cv::cvtColor(vision::image::view(frame_), bgr_, cv::COLOR_RGB2BGR);
    cv::imshow(title_, bgr_);
    cv::waitKey(1);
  }

  void deactivate() override {
    if (!headless_) cv::destroyWindow(title_);
  }

 private:
  std::string title_;
  bool headless_ = true;
  cv::Mat bgr_;
  msg::Image frame_;
  Input<msg::Image> in_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::Display, "display")
