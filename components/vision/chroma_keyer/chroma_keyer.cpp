// chroma_keyer: the live image of the user's hand out of the camera image (paper section 2.2,
// STEP 2): everything in the working space is blue cloth except the hand (and the plate). A soft
// alpha from the distance in the YCrCb chroma plane to the key colour, between an inner radius
// (fully keyed out) and an outer one (fully kept); blue spill suppressed on what is kept; an
// optional small opening of the matte. Out: the despilled hand as premultiplied RGBA.
// All whole-image OpenCV operations: no per-pixel calls.
#include <opencv2/imgproc.hpp>

#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision {

class ChromaKeyer final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("soft chroma key against the blue cloth: premultiplied RGBA hand, spill suppressed");
    key_ = ctx.param<std::vector<double>>("key_color", {26, 41, 158}, "the cloth's colour, RGB 0..255", Range{0, 255});
    inner_ = ctx.param<double>("inner", 22, "chroma distance (YCrCb, 0..255) up to which a pixel is cloth", Range{0, 255});
    outer_ = ctx.param<double>("outer", 40, "chroma distance from which a pixel is fully kept", Range{0, 255});
    min_luma_ = ctx.param<double>("min_luma", 12, "darker pixels count as cloth in shadow (Y, 0..255)", Range{0, 255});
    despill_ = ctx.param<bool>("despill", true, "limit blue to max(red, green) on kept pixels");
    morph_ = ctx.param<int>("open_radius", 0, "morphological opening of the matte, px (0: none)", Range{0, 10});
    in_ = ctx.input<msg::Image>("image", "camera image, rgb8", Qos::sensor(2));
    hand_ = ctx.output<msg::Image>("hand", "the keyed hand, rgba8, premultiplied", Qos::sensor(2));
    matte_ = ctx.output<msg::Image>("matte", "the alpha matte, mono8", Qos::sensor(2));
    if (key_.size() != 3) throw std::invalid_argument("key_color: expected three numbers r g b");
    if (!(outer_ > inner_)) throw std::invalid_argument("outer must be larger than inner");
    const cv::Mat key(1, 1, CV_8UC3, cv::Scalar(key_[0], key_[1], key_[2]));
    cv::Mat ycc;
    cv::cvtColor(key, ycc, cv::COLOR_RGB2YCrCb);
    key_cr_ = ycc.at<cv::Vec3b>(0)[1];
    key_cb_ = ycc.at<cv::Vec3b>(0)[2];
  }

  void tick(Time now) override {
    if (!in_.take_latest(frame_)) return;
    if (std::string(frame_.encoding().c_str()) != "rgb8" || frame_.step() < frame_.width() * 3 ||
        frame_.data().size() < static_cast<std::size_t>(frame_.step()) * frame_.height())
      return;  // not an rgb8 frame: nothing to key
    const cv::Mat rgb(static_cast<int>(frame_.height()), static_cast<int>(frame_.width()), CV_8UC3, frame_.data().data(),
                      frame_.step());
    key(rgb);
    publish(now);
  }

 private:
  void key(const cv::Mat& rgb) {
    cv::cvtColor(rgb, ycc_, cv::COLOR_RGB2YCrCb);
    cv::split(ycc_, planes_);
    planes_[1].convertTo(cr_, CV_32F, 1.0, -key_cr_);
    planes_[2].convertTo(cb_, CV_32F, 1.0, -key_cb_);
    cv::magnitude(cr_, cb_, distance_);
    // alpha = (d - inner) / (outer - inner), clamped to [0, 1] by the 8-bit conversion.
    distance_.convertTo(alpha_, CV_8U, 255.0 / (outer_ - inner_), -255.0 * inner_ / (outer_ - inner_));
    if (min_luma_ > 0) alpha_.setTo(0, planes_[0] < min_luma_);
    if (morph_ > 0)
      cv::morphologyEx(alpha_, alpha_, cv::MORPH_OPEN,
                       cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * morph_ + 1, 2 * morph_ + 1)));
    cv::split(rgb, rgb_planes_);
    if (despill_) {  // blue spill: blue may not exceed the larger of red and green
      cv::max(rgb_planes_[0], rgb_planes_[1], limit_);
      cv::min(rgb_planes_[2], limit_, rgb_planes_[2]);
    }
    for (auto& p : rgb_planes_) cv::multiply(p, alpha_, p, 1.0 / 255.0);  // premultiply
    rgb_planes_.push_back(alpha_);
    cv::merge(rgb_planes_, rgba_);
  }

  void publish(Time now) {
    auto fill = [&](msg::Image& m, const cv::Mat& img, const char* encoding) {
      m.header() = frame_.header();
      m.header().stamp_ns(frame_.header().stamp_ns() ? frame_.header().stamp_ns() : now.ns);
      m.width(static_cast<std::uint32_t>(img.cols)), m.height(static_cast<std::uint32_t>(img.rows));
      m.encoding(encoding);
      m.step(static_cast<std::uint32_t>(img.cols * img.elemSize()));
      m.data().assign(img.data, img.data + img.total() * img.elemSize());
    };
    fill(hand_msg_, rgba_, "rgba8");
    hand_.write(hand_msg_);
    fill(matte_msg_, alpha_, "mono8");
    matte_.write(matte_msg_);
  }

  std::vector<double> key_;
  double inner_ = 22, outer_ = 40, min_luma_ = 12, key_cr_ = 0, key_cb_ = 0;
  bool despill_ = true;
  int morph_ = 0;
  cv::Mat ycc_, cr_, cb_, distance_, alpha_, limit_, rgba_;
  std::vector<cv::Mat> planes_, rgb_planes_;
  msg::Image frame_, hand_msg_, matte_msg_;
  Input<msg::Image> in_;
  Output<msg::Image> hand_, matte_;
};

}  // namespace wysiwyf::vision

WYSIWYF_COMPONENT(wysiwyf::vision::ChromaKeyer, "chroma_keyer")
