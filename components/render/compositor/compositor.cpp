// compositor: the user's view (paper section 2.2, STEP 2 and Fig. 3): the keyed live image of the
// hand over the rendered virtual scene. The hand comes premultiplied (RGBA from chroma_keyer):
// out = hand + (1 - alpha) * scene. When the real scene's depth is known (stereo), it z-keys per
// pixel instead: the hand shows only where it is nearer than the virtual surface (section 3.2's
// answer to the hand always being drawn on top). With the device's depth (device_mask: the real
// plate, knob, lamps and arm from the robot model), the device is kept out of the real layer:
// a keyed pixel on the device shows only where the real depth puts something nearer than the
// device (a finger on the plate), so depth decides only between the hand and the virtual scene.
#include <array>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

#include "image/image_view.hpp"
#include "image/pixel_math.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::render {

namespace {

// The depths a blend consults (empty: not there). real: the real scene's (0 unknown); virt: the
// rendered scene's (0 nothing); device: the real device's (0 not there).
struct Depths {
  cv::Mat real, virt, device;
  float margin = 0, device_margin = 0;
};

// Whether the device hides a keyed pixel: the device is there and the real depth does not put
// something nearer than it by device_margin (unknown or absent real depth: hidden).
inline unsigned device_hides(float device, const float* real, int x, float device_margin) {
  return device > 0.0f && !(real && real[x] > 0.0f && real[x] < device - device_margin);
}

// out = hand + scene (255 - alpha) / 255 per channel, exactly rounded, in one pass over the
// rows with OpenCV's universal intrinsics (16 pixels at a time; OpenCV's multiply/merge/add
// chain made five passes and a float conversion). kZKey: the hand counts only where no virtual
// surface (depth > 0) is nearer than the real one (depth > 0) plus `margin`. kDevice: nor where
// the device hides it (device_hides).
// shown (optional, mono8): the alpha of the real layer as blended.
template <bool kZKey, bool kDevice>
void blend_rows(const cv::Mat& scene, const cv::Mat& hand, const Depths& d, cv::Mat& composite, cv::Mat* shown) {
  for (int y = 0; y < scene.rows; ++y) {
    const std::uint8_t* sc = scene.ptr<std::uint8_t>(y);
    std::uint8_t* out = composite.ptr<std::uint8_t>(y);
    const std::uint8_t* h = hand.ptr<std::uint8_t>(y);
    const float* real = d.real.empty() ? nullptr : d.real.ptr<float>(y);
    const float* virt = kZKey ? d.virt.ptr<float>(y) : nullptr;
    const float* dev = kDevice ? d.device.ptr<float>(y) : nullptr;
    std::uint8_t* alpha = shown ? shown->ptr<std::uint8_t>(y) : nullptr;
    int x = 0;
#if CV_SIMD128
    const cv::v_uint8x16 full = cv::v_setall_u8(255);
    const cv::v_float32x4 zero = cv::v_setall_f32(0.0f), m = cv::v_setall_f32(d.margin),
                          dm = cv::v_setall_f32(d.device_margin);
    for (; x + 16 <= scene.cols; x += 16) {
      cv::v_uint8x16 hr, hg, hb, ha, sr, sg, sb;
      cv::v_load_deinterleave(h + 4 * x, hr, hg, hb, ha);
      cv::v_load_deinterleave(sc + 3 * x, sr, sg, sb);
      if constexpr (kZKey || kDevice) {
        cv::v_uint32x4 hidden[4];
        for (int k = 0; k < 4; ++k) {
          cv::v_float32x4 gone = cv::v_reinterpret_as_f32(cv::v_setzero_u32());
          if constexpr (kZKey) {
            const cv::v_float32x4 vz = cv::v_load(virt + x + 4 * k), rz = cv::v_load(real + x + 4 * k);
            gone = gone | ((vz > zero) & (rz > zero) & (vz < rz + m));
          }
          if constexpr (kDevice) {
            const cv::v_float32x4 dz = cv::v_load(dev + x + 4 * k);
            cv::v_float32x4 on = dz > zero;
            if (real) {
              const cv::v_float32x4 rz = cv::v_load(real + x + 4 * k);
              on = on & ~((rz > zero) & (rz < dz - dm));
            }
            gone = gone | on;
          }
          hidden[k] = cv::v_reinterpret_as_u32(gone);
        }
        const cv::v_uint8x16 keep = ~cv::v_pack(cv::v_pack(hidden[0], hidden[1]), cv::v_pack(hidden[2], hidden[3]));
        hr = hr & keep, hg = hg & keep, hb = hb & keep, ha = ha & keep;
      }
      if (alpha) cv::v_store(alpha + x, ha);
      const cv::v_uint8x16 inverse = full - ha;
      // (+ saturates on 8 bits; the sum cannot pass 255 anyway: the hand is premultiplied)
      cv::v_store_interleave(out + 3 * x, hr + vision::image::mul_div255(sr, inverse),
                             hg + vision::image::mul_div255(sg, inverse), hb + vision::image::mul_div255(sb, inverse));
    }
#endif
    for (; x < scene.cols; ++x) {
      unsigned keep = 1;  // 0 where the virtual surface or the device hides the hand
      if constexpr (kZKey) keep = !(virt[x] > 0.0f && real[x] > 0.0f && virt[x] < real[x] + d.margin);
      if constexpr (kDevice) keep &= !device_hides(dev[x], real, x, d.device_margin);
      const unsigned a = h[4 * x + 3] * keep, inverse = 255u - a;
      if (alpha) alpha[x] = static_cast<std::uint8_t>(a);
      for (int c = 0; c < 3; ++c) {
        const unsigned blended = h[4 * x + c] * keep + vision::image::mul_div255(sc[3 * x + c], inverse);
        out[3 * x + c] = static_cast<std::uint8_t>(blended > 255u ? 255u : blended);
      }
    }
  }
}

void blend(const cv::Mat& scene, const cv::Mat& hand, const Depths& d, bool z_key, cv::Mat& composite, cv::Mat* shown) {
  const bool device = !d.device.empty();
  if (z_key && device)
    blend_rows<true, true>(scene, hand, d, composite, shown);
  else if (z_key)
    blend_rows<true, false>(scene, hand, d, composite, shown);
  else if (device)
    blend_rows<false, true>(scene, hand, d, composite, shown);
  else
    blend_rows<false, false>(scene, hand, d, composite, shown);
}

}  // namespace

class Compositor final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("the keyed hand over the rendered scene: premultiplied alpha, or z-keying with depth");
    use_depth_ = ctx.param<bool>("z_keying", true, "z-key when the real scene's depth arrives (else alpha only)");
    margin_ = static_cast<float>(ctx.param<double>(
        "z_margin", 0.0,
        "m: z-keying shows the real scene only where it is nearer than the virtual surface by more than this "
        "(a few mm hide stereo noise on real things lying on a virtual surface, like the plate on the cube's face; "
        "a fingertip thinner than it, touching, is hidden too)",
        Range{0, 0.1}));
    scene_in_ = ctx.input<msg::Image>("scene", "the rendered virtual scene, rgb8", Qos::sensor(2));
    scene_depth_in_ = ctx.input<msg::Image>("scene_depth", "its metric depth, 32FC1 (0: nothing)", Qos::sensor(2));
    hand_in_ = ctx.input<msg::Image>("hand", "the keyed hand, rgba8 premultiplied", Qos::sensor(2));
    real_depth_in_ =
        ctx.input<msg::Image>("real_depth", "metric depth of the real scene, 32FC1 (0: unknown)", Qos::sensor(2));
    camera_in_ =
        ctx.input<msg::Image>("camera", "instead of hand: the camera image, rgb8 ...", Qos::sensor(2).optional_input());
    mask_in_ = ctx.input<msg::Image>("hand_mask", "... and a hand mask, mono8 (a hardware keyer, or ground truth)",
                                     Qos::sensor(2).optional_input());
    device_in_ = ctx.input<msg::Image>("device_depth",
                                       "the real device's depth (device_mask), 32FC1: kept out of the real layer",
                                       Qos::sensor(2).optional_input());
    device_margin_ = static_cast<float>(ctx.param<double>(
        "device_margin", 0.0, "m a keyed pixel on the device must be nearer than the device to count as hand",
        Range{0, 0.1}));
    device_edge_px_ = ctx.param<int>(
        "device_edge_px", 0,
        "px: a keyed pixel on the device shows only where the real depth puts something nearer than the device at "
        "every pixel within this distance along its row too (stereo matching along the rows spreads a near edge's "
        "depth sideways over the far side by about half its window: without this the device shows beside a finger)",
        Range{0, 32});
    match_frames_ = ctx.param<bool>(
        "match_frames", false,
        "composite only layers of one camera frame: the scene (stamped with its eye_T_base's frame), the hand, and "
        "the depths once they arrive, all with one stamp (for data-triggered ticks: trigger on all of them)");
    out_ = ctx.output<msg::Image>("composite", "what the user sees, rgb8", Qos::sensor(2));
    publish_shown_ = ctx.param<bool>("publish_shown", false, "publish `shown` (for metrics)");
    shown_out_ = ctx.output<msg::Image>(
        "shown",
        "with publish_shown: the real layer's alpha as blended, mono8, stamped with the hand image's stamp "
        "(the camera's), with the composite's seq",
        Qos::sensor(2));
  }

  void tick(Time now) override {
    bool fresh = take(scene_in_, scene_, {"rgb8"});
    fresh |= match_frames_ ? take_hands() : take(hand_in_, hand_, {"rgba8"});
    if (take(camera_in_, camera_, {"rgb8"}) | take(mask_in_, mask_, {"mono8"})) fresh |= hand_from_mask();
    const bool depths = take(scene_depth_in_, scene_depth_, {"32FC1"}) | take(real_depth_in_, real_depth_, {"32FC1"}) |
                        take(device_in_, device_, {"32FC1"});
    if (match_frames_) {
      pick_hand();
      if (!(fresh || depths) || !one_frame()) return;
      composited_stamp_ = scene_.image.header().stamp_ns();
    } else if (!fresh || !scene_.usable) {
      return;
    }
    const std::uint32_t w = scene_.image.width(), h = scene_.image.height();
    // The composite is written straight into the outgoing message (sized once).
    cv::Mat out = vision::image::allocate(out_msg_, static_cast<int>(w), static_cast<int>(h), "rgb8");
    const std::uint64_t seq = seq_++;  // the composite's and its `shown` alpha's
    fill_header(out_msg_.header(), now.ns, seq, scene_.image.header().frame_id().c_str());
    const cv::Mat scene = vision::image::view(scene_.image);
    if (same_size(hand_in_, hand_, w, h)) {
      Depths d;
      d.margin = margin_, d.device_margin = device_margin_;
      if (same_size(real_depth_in_, real_depth_, w, h)) d.real = vision::image::view(real_depth_.image);
      const bool z_key = use_depth_ && !d.real.empty() && same_size(scene_depth_in_, scene_depth_, w, h);
      if (z_key) d.virt = vision::image::view(scene_depth_.image);
      if (same_size(device_in_, device_, w, h)) d.device = vision::image::view(device_.image);
      if (device_edge_px_ > 0 && !d.device.empty() && !d.real.empty()) shrink_nearer(d);
      cv::Mat shown;
      if (publish_shown_) {
        shown = vision::image::allocate(shown_msg_, static_cast<int>(w), static_cast<int>(h), "mono8");
        fill_header(shown_msg_.header(), hand_.image.header().stamp_ns(), seq, "eye");
      }
      blend(scene, vision::image::view(hand_.image), d, z_key, out, publish_shown_ ? &shown : nullptr);
      if (publish_shown_) shown_out_.write(shown_msg_);
    } else {
      scene.copyTo(out);
    }
    out_.write(out_msg_);
  }

 private:
  // The device's depth where something nearer than it shows through, less device_edge_px_ on
  // either side, along the rows, of every edge of that region inside the device: there the device
  // hides whatever the real depth says (device_margin then plays no further part). Along the
  // rows only: the pair's disparity is horizontal, and a fingertip pointing up keeps its length.
  void shrink_nearer(Depths& d) {
    cv::subtract(d.device, d.real, gap_);
    cv::Mat shows = (d.real > 0.0f) & (gap_ > d.device_margin);  // nearer than the device
    shows |= d.device <= 0.0f;                                   // (off the device: no edge to shrink from)
    const int k = 2 * device_edge_px_ + 1;
    cv::erode(shows, shows_, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, 1)));
    d.device.copyTo(device_shrunk_);
    device_shrunk_.setTo(0.0f, shows_);
    d.device = device_shrunk_;
    d.device_margin = std::numeric_limits<float>::infinity();
  }

  // An input image and whether it can be used (a rejected one is not, until the next arrives).
  struct Stream {
    msg::Image image;
    bool usable = false;
    bool seen = false;  // a sample has come (match_frames waits for this layer from then on)
  };

  // The newest sample of `in` into `s`; a wrong one is rejected. True when a usable one came.
  bool take(Input<msg::Image>& in, Stream& s, std::initializer_list<std::string_view> encodings) {
    return in.take_latest(s.image) && accept(in, s, encodings);
  }
  // The sample just taken into `s`: usable, or rejected. True when usable.
  bool accept(Input<msg::Image>& in, Stream& s, std::initializer_list<std::string_view> encodings) {
    s.seen = true;
    const std::string bad = vision::image::problem(s.image, encodings);
    s.usable = bad.empty();
    if (!s.usable) reject(in, bad);
    return s.usable;
  }
  // Whether `s` is usable with a w x h scene; one of another size is rejected (once).
  bool same_size(const Input<msg::Image>& in, Stream& s, std::uint32_t w, std::uint32_t h) {
    if (!s.usable) return false;
    if (s.image.width() == w && s.image.height() == h) return true;
    reject(in, "size " + std::to_string(s.image.width()) + "x" + std::to_string(s.image.height()) +
                   ", not the scene's " + std::to_string(w) + "x" + std::to_string(h));
    s.usable = false;
    return false;
  }

  // match_frames: every queued hand into a short history (the keyer runs ahead of the renderer),
  // and hand_ the one of the scene's frame when it is there.
  bool take_hands() {
    bool any = false;
    while (hand_in_.take(hands_[next_hand_].image)) {
      any |= accept(hand_in_, hands_[next_hand_], {"rgba8"});
      next_hand_ = (next_hand_ + 1) % hands_.size();
    }
    return any;
  }
  void pick_hand() {
    if (!scene_.usable) return;
    const std::int64_t stamp = scene_.image.header().stamp_ns();
    for (auto& h : hands_)
      if (h.usable && h.image.header().stamp_ns() == stamp && hand_.image.header().stamp_ns() != stamp) {
        using std::swap;
        swap(hand_, h);
        h.usable = false;
      }
  }

  // match_frames: whether every layer that has come is of the scene's camera frame, and that
  // frame is not composited yet.
  bool one_frame() const {
    if (!scene_.usable || !hand_.usable) return false;
    const std::int64_t stamp = scene_.image.header().stamp_ns();
    if (stamp == composited_stamp_ || hand_.image.header().stamp_ns() != stamp) return false;
    for (const Stream* s : {&scene_depth_, &real_depth_, &device_})
      if (s->seen && s->image.header().stamp_ns() != stamp) return false;
    return true;
  }

  // A premultiplied RGBA hand layer from a camera image and a 0/255 mask of the same size.
  bool hand_from_mask() {
    if (!camera_.usable || !same_size(mask_in_, mask_, camera_.image.width(), camera_.image.height())) return false;
    cv::Mat rgba = vision::image::allocate(hand_.image, static_cast<int>(camera_.image.width()),
                                           static_cast<int>(camera_.image.height()), "rgba8");
    const cv::Mat cam = vision::image::view(camera_.image), mask = vision::image::view(mask_.image);
    cv::Mat premultiplied;
    cam.copyTo(premultiplied);
    premultiplied.setTo(0, ~mask);
    const cv::Mat channels[] = {premultiplied, mask};
    int from_to[] = {0, 0, 1, 1, 2, 2, 3, 3};
    cv::mixChannels(channels, 2, &rgba, 1, from_to, 4);
    hand_.image.header(camera_.image.header());  // the camera's stamp: the frame it shows
    hand_.usable = true;
    return true;
  }

  bool use_depth_ = true;
  int device_edge_px_ = 0;
  cv::Mat gap_, shows_, device_shrunk_;  // shrink_nearer's
  float margin_ = 0.0f, device_margin_ = 0.0f;
  bool publish_shown_ = false;
  bool match_frames_ = false;
  std::array<Stream, 4> hands_;  // match_frames: the latest hands, by arrival
  std::size_t next_hand_ = 0;
  std::int64_t composited_stamp_ = -1;
  msg::Image shown_msg_;
  Output<msg::Image> shown_out_;
  std::uint64_t seq_ = 0;
  Stream scene_, scene_depth_, hand_, real_depth_, camera_, mask_, device_;
  msg::Image out_msg_;
  Input<msg::Image> scene_in_, scene_depth_in_, hand_in_, real_depth_in_, camera_in_, mask_in_, device_in_;
  Output<msg::Image> out_;
};

}  // namespace wysiwyf::render

WYSIWYF_COMPONENT(wysiwyf::render::Compositor, "compositor")
