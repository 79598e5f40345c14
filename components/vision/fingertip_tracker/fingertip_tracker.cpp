// fingertip_tracker: where the user's fingertip is, from a small light on it (an LED on the
// fingernail) seen by a rectified stereo pair: the hand tracking the paper cites for the surface
// display ("a video camera that tracks an infrared LED attached at the user's fingertip";
// McNeely's system used two cameras). In the left image the LED is the light of its colour
// (libs/vision/bright_blobs: a colour channel's excess over the others, or plain brightness for an
// infrared camera) looked for in a search window around where it was predicted (constant velocity
// in the image from the last two fixes), the whole image when there is no track; in the right
// image along the same row (rectified: epipolar lines are rows), within the disparities of the
// depth range. The disparity gives depth, the camera pose (eye_T_base) the base frame; the
// covariance comes from the centroids' noise through the triangulation, plus where on the finger
// the LED sits. Each stereo pair gives a HandPosition stamped with the images' time: OK, or LOST
// after `lost_after` pairs without the LED.
#include <cmath>
#include <string_view>

#include "bright_blobs/blob_detector.hpp"
#include "image/image_view.hpp"
#include "stereo_intake/stereo_intake.hpp"
#include "stereo_point.hpp"
#include "wysiwyf/camera_info.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision {

class FingertipTracker final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("the fingertip from an LED on it seen by a rectified stereo pair: HandPosition in base");
    const auto colour = ctx.param_choice(
        "colour", "green",
        "the LED's colour: its channel's excess over the other two is its brightness; bright: the luma (an infrared "
        "camera)",
        {"red", "green", "blue", "bright"});
    BlobSettings blobs;
    blobs.brightness = colour == "red"     ? Brightness::kRedExcess
                       : colour == "green" ? Brightness::kGreenExcess
                       : colour == "blue"  ? Brightness::kBlueExcess
                                           : Brightness::kLuma;
    blobs.threshold = ctx.param<int>("threshold", colour == "bright" ? 230 : 70,
                                     "brightness (0..255) above which a pixel is LED", Range{1, 254});
    blobs.min_area = ctx.param<int>("min_area", 2, "smallest LED blob, px", Range{1, 10000});
    blobs.max_area = ctx.param<int>("max_area", 1500, "largest LED blob, px", Range{1, 100000});
    blobs.min_fill = 0.3;
    pixel_sigma_ = ctx.param<double>("pixel_sigma", 0.3, "an LED centroid's noise, px", Range{0.01, 20});
    offset_sigma_ = ctx.param<double>(
        "marker_offset_sigma", 0.01,
        "m: where the LED sits from the fingertip's centre (on the nail, about a finger's radius away), as noise",
        Range{0, 0.1});
    min_depth_ = ctx.param<double>("min_depth", 0.2, "nearest LED looked for, m", Range{0.01, 100});
    max_depth_ = ctx.param<double>("max_depth", 3.0, "farthest LED looked for, m", Range{0.01, 100});
    row_tolerance_ = ctx.param<double>("row_tolerance", 1.5,
                                       "px the right image's LED may lie off the left one's row (rectification error)",
                                       Range{0.1, 50});
    min_window_ = ctx.param<int>("min_window", 16, "search window half size at least, px", Range{2, 1000});
    max_window_ = ctx.param<int>("max_window", 120, "search window half size at most, px", Range{2, 2000});
    lost_after_ =
        ctx.param<int>("lost_after", 3, "stereo pairs without the LED before the hand is LOST", Range{1, 1000});
    pair_.configure(ctx, {"rgb8", "bgr8", "mono8"});
    eye_T_base_in_ =
        ctx.input<msg::PoseStamped>("eye_T_base", "the camera's pose (tracker or calibration)", Qos::sensor(4));
    hand_out_ = ctx.output<msg::HandPosition>("hand", "the fingertip in base, with covariance; LOST when not seen",
                                              Qos::sensor(8));
    if (min_depth_ >= max_depth_) ctx.reject("max_depth", "must be larger than min_depth");
    if (min_window_ > max_window_) ctx.reject("max_window", "must not be below min_window");
    if (blobs.min_area > blobs.max_area) ctx.reject("max_area", "must not be below min_area");
    detector_ = BlobDetector(blobs);
  }

  void tick(Time now) override {
    while (take_checked(eye_T_base_in_, pose_))
      base_T_eye_ = msgs::to_isometry(pose_.pose()).inverse(), have_pose_ = true;
    pair_.read_calibration(complaints_);
    if (!pair_.next_pair(complaints_)) return;
    if (!have_pose_) {
      warn_once("no camera pose yet (eye_T_base); stereo pairs are skipped until it comes");
      return;
    }
    const msgs::CameraIntrinsics& K = pair_.intrinsics();
    camera_.fx = K.fx, camera_.fy = K.fy, camera_.cx = K.cx, camera_.cy = K.cy, camera_.baseline = pair_.baseline();
    const std::int64_t stamp = pair_.left().header().stamp_ns() ? pair_.left().header().stamp_ns() : now.ns;
    if (locate(stamp))
      misses_ = 0;
    else if (++misses_ >= lost_after_)
      publish_lost(stamp);
  }

 private:
  // The LED in both images of the pair, triangulated and published; false when it is not found.
  bool locate(std::int64_t stamp) {
    const std::string_view enc = pair_.left().encoding().c_str();
    const PixelLayout layout = enc == "rgb8"   ? PixelLayout::kRgb8
                               : enc == "bgr8" ? PixelLayout::kBgr8
                                               : PixelLayout::kMono8;
    const cv::Mat left = image::view(pair_.left()), right = image::view(pair_.right());
    // Left: in the window around the prediction; the whole image without a track or when it is not there.
    found_.clear();
    cv::Point2d predicted;
    const bool tracking = fixes_ > 0;
    if (tracking) {
      const double dt = static_cast<double>(stamp - last_ns_) * 1e-9;
      predicted = last_ + velocity_ * dt;
      const double half =
          std::clamp(min_window_ + std::hypot(velocity_.x, velocity_.y) * dt, double(min_window_), double(max_window_));
      const int h = static_cast<int>(std::ceil(half));
      detector_.detect_in(
          left, layout,
          cv::Rect(static_cast<int>(predicted.x) - h, static_cast<int>(predicted.y) - h, 2 * h + 1, 2 * h + 1), found_);
    }
    if (found_.empty()) detector_.detect_all(left, layout, found_);
    // Nearest the prediction; without a track, the one with a partner in the right image.
    std::sort(found_.begin(), found_.end(), [&](const Blob& a, const Blob& b) {
      return tracking
                 ? std::hypot(a.u - predicted.x, a.v - predicted.y) < std::hypot(b.u - predicted.x, b.v - predicted.y)
                 : a.area > b.area;
    });
    for (const Blob& l : found_) {
      const auto u_right = match_right(right, layout, l);
      if (!u_right) continue;
      const auto point = triangulate(camera_, l.u, l.v, *u_right, pixel_sigma_);
      if (!point) continue;
      publish(stamp, *point);
      const cv::Point2d now_px(l.u, l.v);
      if (fixes_ > 0 && stamp > last_ns_) velocity_ = (now_px - last_) * (1e9 / static_cast<double>(stamp - last_ns_));
      last_ = now_px, last_ns_ = stamp, ++fixes_;
      return true;
    }
    fixes_ = 0, velocity_ = {0, 0};  // lost it: search the whole image next time
    return false;
  }

  // The right image's LED on the left one's row, within the depth range's disparities.
  std::optional<double> match_right(const cv::Mat& right, PixelLayout layout, const Blob& l) {
    const double d_max = camera_.fx * camera_.baseline / min_depth_, d_min = camera_.fx * camera_.baseline / max_depth_;
    const int pad = 2 + static_cast<int>(std::ceil(row_tolerance_)) + std::max(l.box.width, l.box.height);
    const cv::Rect band(static_cast<int>(std::floor(l.u - d_max)) - pad, static_cast<int>(std::floor(l.v)) - pad,
                        static_cast<int>(std::ceil(d_max - d_min)) + 2 * pad + 1, 2 * pad + 1);
    right_found_.clear();
    detector_.detect_in(right, layout, band, right_found_);
    std::optional<double> best;
    double best_cost = 1e9;
    for (const Blob& r : right_found_) {
      const double d = l.u - r.u;
      if (std::abs(r.v - l.v) > row_tolerance_ || d < d_min || d > d_max) continue;
      const double cost = std::abs(r.v - l.v) + 0.1 * std::abs(r.area - l.area);
      if (cost < best_cost) best_cost = cost, best = r.u;
    }
    return best;
  }

  void publish(std::int64_t stamp, const StereoPoint& p) {
    fill_header(hand_msg_.header(), stamp, seq_++, "base");
    msgs::to_msg(Eigen::Vector3d(base_T_eye_ * p.eye_p), hand_msg_.position());
    const Eigen::Matrix3d R = base_T_eye_.linear();
    const Eigen::Matrix3d cov =
        R * p.covariance * R.transpose() + offset_sigma_ * offset_sigma_ * Eigen::Matrix3d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) hand_msg_.covariance()[static_cast<std::size_t>(3 * r + c)] = cov(r, c);
    hand_msg_.status(msg::TRACKING_OK);
    hand_msg_.source("fingertip_marker");
    hand_out_.write(hand_msg_);
  }

  void publish_lost(std::int64_t stamp) {
    fill_header(hand_msg_.header(), stamp, seq_++, "base");
    hand_msg_.status(msg::TRACKING_LOST);
    hand_msg_.source("fingertip_marker");
    hand_out_.write(hand_msg_);
  }

  BlobDetector detector_;
  StereoCamera camera_;
  StereoIntake pair_;
  const StereoIntake::Complaints complaints_{
      [this](const Input<msg::Image>& in, const std::string& why) { reject(in, why); },
      [this](const Input<msg::CameraInfo>& in, const std::string& why) { reject(in, why); },
      [this](const std::string& what) { warn_once(what); }};
  double pixel_sigma_ = 0.3, offset_sigma_ = 0.01, min_depth_ = 0.2, max_depth_ = 3, row_tolerance_ = 1.5;
  int min_window_ = 16, max_window_ = 120, lost_after_ = 3, misses_ = 0;
  // the track, in the left image
  int fixes_ = 0;
  cv::Point2d last_{0, 0}, velocity_{0, 0};  // px, px/s
  std::int64_t last_ns_ = 0;
  std::vector<Blob> found_, right_found_;
  Eigen::Isometry3d base_T_eye_ = Eigen::Isometry3d::Identity();
  bool have_pose_ = false;
  std::uint64_t seq_ = 0;
  msg::PoseStamped pose_;
  msg::HandPosition hand_msg_;
  Input<msg::PoseStamped> eye_T_base_in_;
  Output<msg::HandPosition> hand_out_;
};

}  // namespace wysiwyf::vision

WYSIWYF_COMPONENT(wysiwyf::vision::FingertipTracker, "fingertip_tracker")
