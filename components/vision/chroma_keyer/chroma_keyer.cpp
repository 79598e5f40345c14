// chroma_keyer: the live image of the user's hand out of the camera image (paper section 2.2,
// STEP 2): everything in the working space is blue cloth except the hand (and the plate). A soft
// alpha from the distance in the YCrCb chroma plane to the key colour, between an inner radius
// (fully keyed out) and an outer one (fully kept); blue spill suppressed on what is kept; an
// optional small opening of the matte. Out: the despilled hand as premultiplied RGBA.
// Vectorised with OpenCV's universal intrinsics: no per-pixel calls.
#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

#include "image/image_view.hpp"
#include "image/pixel_math.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision {

class ChromaKeyer final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("soft chroma key against the blue cloth: premultiplied RGBA hand, spill suppressed");
    key_ =
        ctx.param<std::array<double, 3>>("key_color", {26, 41, 158}, "the cloth's colour, RGB 0..255", Range{0, 255});
    inner_ =
        ctx.param<double>("inner", 22, "chroma distance (YCrCb, 0..255) up to which a pixel is cloth", Range{0, 255});
    outer_ = ctx.param<double>("outer", 40, "chroma distance from which a pixel is fully kept", Range{0, 255});
    min_luma_ = ctx.param<double>("min_luma", 12, "darker pixels count as cloth in shadow (Y, 0..255)", Range{0, 255});
    despill_ = ctx.param<bool>("despill", true, "limit blue to max(red, green) on kept pixels");
    morph_ = ctx.param<int>("open_radius", 0, "morphological opening of the matte, px (0: none)", Range{0, 10});
    in_ = ctx.input<msg::Image>("image", "camera image, rgb8", Qos::sensor(2));
    hand_ = ctx.output<msg::Image>("hand", "the keyed hand, rgba8, premultiplied", Qos::sensor(2));
    matte_ = ctx.output<msg::Image>("matte", "the alpha matte, mono8", Qos::sensor(2));
    if (!(outer_ > inner_)) ctx.reject("outer", "must be larger than inner (" + std::to_string(inner_) + ")");
    const cv::Mat key(1, 1, CV_8UC3, cv::Scalar(key_[0], key_[1], key_[2]));
    cv::Mat ycc;
    cv::cvtColor(key, ycc, cv::COLOR_RGB2YCrCb);
    key_cr_ = ycc.at<cv::Vec3b>(0)[1];
    key_cb_ = ycc.at<cv::Vec3b>(0)[2];
  }

  void tick(Time now) override {
    if (!in_.take_latest(frame_)) return;
    if (const std::string bad = image::problem(frame_, {"rgb8"}); !bad.empty()) return reject(in_, bad);
    key(image::view(frame_));
    publish(now);
  }

 private:
  // Two passes over the rows with OpenCV's universal intrinsics (16 pixels at a time, scalar
  // tails): the matte, then (after the optional opening) despill + premultiply + interleave
  // straight into the outgoing messages. Chroma as in ITU-R BT.601 (OpenCV's YCrCb):
  // Y = .299 R + .587 G + .114 B, Cr = .713 (R - Y) + 128, Cb = .564 (B - Y) + 128.
  void key(const cv::Mat& rgb) {
    const int w = rgb.cols, h = rgb.rows;
    alpha_ = image::allocate(matte_msg_, w, h, "mono8");
    image::allocate(hand_msg_, w, h, "rgba8");
    const float gain = static_cast<float>(255.0 / (outer_ - inner_)), inner = static_cast<float>(inner_);
    const float dcr0 = static_cast<float>(128.0 - key_cr_), dcb0 = static_cast<float>(128.0 - key_cb_);
    const float min_luma = static_cast<float>(min_luma_);
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* in = rgb.ptr<std::uint8_t>(y);
      std::uint8_t* alpha = alpha_.ptr<std::uint8_t>(y);
      int x = 0;
#if CV_SIMD128
      const cv::v_float32x4 kr = cv::v_setall_f32(0.299f), kg = cv::v_setall_f32(0.587f), kb = cv::v_setall_f32(0.114f),
                            kcr = cv::v_setall_f32(0.713f), kcb = cv::v_setall_f32(0.564f),
                            vcr0 = cv::v_setall_f32(dcr0), vcb0 = cv::v_setall_f32(dcb0),
                            vinner = cv::v_setall_f32(inner), vgain = cv::v_setall_f32(gain),
                            vluma = cv::v_setall_f32(min_luma), zero = cv::v_setall_f32(0.0f);
      // alpha of 4 pixels as int32
      auto alpha4 = [&](const cv::v_uint32x4& r, const cv::v_uint32x4& g, const cv::v_uint32x4& b) {
        const cv::v_float32x4 fr = cv::v_cvt_f32(cv::v_reinterpret_as_s32(r)),
                              fg = cv::v_cvt_f32(cv::v_reinterpret_as_s32(g)),
                              fb = cv::v_cvt_f32(cv::v_reinterpret_as_s32(b));
        const cv::v_float32x4 luma = fr * kr + fg * kg + fb * kb;
        const cv::v_float32x4 dcr = (fr - luma) * kcr + vcr0, dcb = (fb - luma) * kcb + vcb0;
        cv::v_float32x4 a = (cv::v_sqrt(dcr * dcr + dcb * dcb) - vinner) * vgain;
        a = cv::v_select(luma < vluma, zero, a);
        return cv::v_round(a);
      };
      for (; x + 16 <= w; x += 16) {
        cv::v_uint8x16 r, g, b;
        cv::v_load_deinterleave(in + 3 * x, r, g, b);
        cv::v_uint16x8 r16[2], g16[2], b16[2];
        cv::v_expand(r, r16[0], r16[1]);
        cv::v_expand(g, g16[0], g16[1]);
        cv::v_expand(b, b16[0], b16[1]);
        cv::v_int32x4 a32[4];
        for (int k = 0; k < 2; ++k) {
          cv::v_uint32x4 r0, r1, g0, g1, b0, b1;
          cv::v_expand(r16[k], r0, r1);
          cv::v_expand(g16[k], g0, g1);
          cv::v_expand(b16[k], b0, b1);
          a32[2 * k] = alpha4(r0, g0, b0);
          a32[2 * k + 1] = alpha4(r1, g1, b1);
        }
        // saturating packs clamp to [0, 255]
        cv::v_store(alpha + x, cv::v_pack_u(cv::v_pack(a32[0], a32[1]), cv::v_pack(a32[2], a32[3])));
      }
#endif
      for (; x < w; ++x) {
        const float r = in[3 * x], g = in[3 * x + 1], b = in[3 * x + 2];
        const float luma = 0.299f * r + 0.587f * g + 0.114f * b;
        const float dcr = (r - luma) * 0.713f + dcr0, dcb = (b - luma) * 0.564f + dcb0;
        const float a = luma < min_luma ? 0.0f : (std::sqrt(dcr * dcr + dcb * dcb) - inner) * gain;
        alpha[x] = static_cast<std::uint8_t>(std::clamp(std::lround(a), 0L, 255L));
      }
    }
    if (morph_ > 0)
      cv::morphologyEx(alpha_, alpha_, cv::MORPH_OPEN,
                       cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * morph_ + 1, 2 * morph_ + 1)));
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* in = rgb.ptr<std::uint8_t>(y);
      const std::uint8_t* alpha = alpha_.ptr<std::uint8_t>(y);
      std::uint8_t* out = hand_msg_.data().data() + static_cast<std::size_t>(y) * w * 4;
      int x = 0;
#if CV_SIMD128
      for (; x + 16 <= w; x += 16) {
        cv::v_uint8x16 r, g, b;
        cv::v_load_deinterleave(in + 3 * x, r, g, b);
        const cv::v_uint8x16 a = cv::v_load(alpha + x);
        if (despill_) b = cv::v_min(b, cv::v_max(r, g));  // blue spill: blue may not exceed max(red, green)
        cv::v_store_interleave(out + 4 * x, image::mul_div255(r, a), image::mul_div255(g, a), image::mul_div255(b, a),
                               a);
      }
#endif
      for (; x < w; ++x) {
        const unsigned a = alpha[x];
        const unsigned r = in[3 * x], g = in[3 * x + 1];
        const unsigned b = despill_ ? std::min<unsigned>(in[3 * x + 2], std::max(r, g)) : in[3 * x + 2];
        const unsigned c[3] = {r, g, b};
        for (int k = 0; k < 3; ++k) out[4 * x + k] = static_cast<std::uint8_t>(image::mul_div255(c[k], a));
        out[4 * x + 3] = static_cast<std::uint8_t>(a);
      }
    }
  }

  void publish(Time now) {
    for (msg::Image* m : {&hand_msg_, &matte_msg_}) {
      m->header() = frame_.header();
      m->header().stamp_ns(frame_.header().stamp_ns() ? frame_.header().stamp_ns() : now.ns);
    }
    hand_.write(hand_msg_);
    matte_.write(matte_msg_);
  }

  std::array<double, 3> key_{};
  double inner_ = 22, outer_ = 40, min_luma_ = 12, key_cr_ = 0, key_cb_ = 0;
  bool despill_ = true;
  int morph_ = 0;
  cv::Mat alpha_;  // the matte, a view of matte_msg_'s buffer
  msg::Image frame_, hand_msg_, matte_msg_;
  Input<msg::Image> in_;
  Output<msg::Image> hand_, matte_;
};

}  // namespace wysiwyf::vision

WYSIWYF_COMPONENT(wysiwyf::vision::ChromaKeyer, "chroma_keyer")
