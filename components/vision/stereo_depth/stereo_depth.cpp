// stereo_depth: the real scene's depth from a rectified stereo pair, for the compositor's
// z-keying (paper section 3.2: the hand must disappear behind a virtual object nearer than it),
// and the hand's 3D position from the keyed pixels with depth, for the surface-display planner
// (section 3.2's suggestion: put the plate where the hand is about to touch). The depth image is
// the left (reference) camera's; the hand is published in the eye frame, or in the base frame
// once eye_T_base arrives; with eye_T_dev the keyed plate and knob are left out of the hand.
#include <opencv2/imgproc.hpp>

#include <array>
#include <string_view>

#include "disparity_depth.hpp"
#include "hand_point.hpp"
#include "image/image_view.hpp"
#include "stereo_intake/stereo_intake.hpp"
#include "wysiwyf/camera_info.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision {

class StereoDepth final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("depth from a rectified stereo pair (z-keying) and the keyed hand's 3D position");
    StereoSettings s;
    s.algorithm = ctx.param_choice("algorithm", "sgbm",
                                   "bm: block matching; sgbm: semi-global, 5 paths; sgbm_3way: 3 paths, threaded",
                                   {"bm", "sgbm", "sgbm_3way"});
    s.num_disparities = ctx.param<int>(
        "num_disparities", 0, "disparity search range at the matched size, a multiple of 16 (0: from the depth range)",
        Range{0, 512});
    s.block_size = ctx.param<int>("block_size", 5, "matching window, px, odd (bm: at least 5)", Range{1, 31});
    // Half size by default: several times faster than full size, the hand's position nearly as
    // close (scripts/bench vision measures both; test_stereo_depth holds the accuracy).
    s.downscale = ctx.param<int>("downscale", 2,
                                 "match on images this many times smaller (speed), depth upsampled back", Range{1, 4});
    s.min_depth = ctx.param<double>("min_depth", 0.3, "nearest depth measured, m", Range{0.01, 100});
    s.max_depth = ctx.param<double>("max_depth", 3.0, "farthest depth measured, m", Range{0.01, 100});
    s.uniqueness_ratio = ctx.param<int>("uniqueness_ratio", 10,
                                        "the best match must beat the second by this many percent", Range{0, 100});
    s.speckle_window =
        ctx.param<int>("speckle_window", 100,
                       "disparity blobs smaller than this (px, matched size) are dropped (0: none)", Range{0, 10000});
    const std::string point = ctx.param_choice(
        "hand_point", "centroid",
        "centroid: centre of the hand's visible surface; nearest: of its part nearest the camera; tip: the pointing "
        "fingertip (the centroid where no finger points out)",
        {"centroid", "nearest", "tip"});
    hand_.point = point == "tip"       ? HandPointOptions::Point::kTip
                  : point == "nearest" ? HandPointOptions::Point::kNearest
                                       : HandPointOptions::Point::kCentroid;
    hand_.nearest_fraction = ctx.param<double>(
        "nearest_fraction", 0.1, "hand_point nearest: this fraction of the hand's pixels", Range{0.001, 1});
    hand_.band = ctx.param<double>(
        "hand_band", 0.08, "hand pixels farther than this from their median depth are dropped, m", Range{0.001, 1});
    hand_.min_alpha =
        ctx.param<int>("hand_alpha", 128, "alpha (0..255) from which a keyed pixel is hand", Range{1, 255});
    // A hand at max_depth (3 m) still covers about 600 px at fx 600; stray keyed specks (lamp glints,
    // the plate's rim) stay below 300 in demo-stereo.
    hand_.min_pixels =
        ctx.param<int>("min_hand_pixels", 300, "fewer hand pixels with depth: no hand position", Range{1, 1e6});
    // The plate (0.2 x 0.2 x 0.01 m behind dev's z = 0), its lamps and its 0.04 m knob (config/robots/puma560.urdf),
    // 1 cm around, 2 cm in front of the knob: the small knob top's stereo depth comes up to 1.5 cm too near at 0.6 m.
    const auto box = ctx.param<std::array<double, 6>>(
        "device_box", {-0.11, 0.11, -0.11, 0.11, -0.02, 0.06},
        "with eye_T_dev: keyed points in this box (dev frame, xmin xmax ymin ymax zmin zmax, m) are device, not hand");
    pair_.configure(ctx, {"rgb8", "mono8"});
    keyed_in_ = ctx.input<msg::Image>("keyed", "optional: the keyer's rgba8 hand of the left image (alpha = hand)",
                                      Qos::sensor(2).optional_input());
    eye_T_base_in_ = ctx.input<msg::PoseStamped>(
        "eye_T_base", "optional: the camera's pose; the hand is then given in base", Qos::sensor(4).optional_input());
    eye_T_dev_in_ =
        ctx.input<msg::PoseStamped>("eye_T_dev", "optional: the device plate's pose; keyed points on it are not hand",
                                    Qos::sensor(4).optional_input());
    depth_out_ =
        ctx.output<msg::Image>("depth", "metric depth of the left image, 32FC1, 0 where unknown", Qos::sensor(2));
    hand_out_ = ctx.output<msg::HandPosition>("hand_position", "the hand's 3D point (in hand_frame) with covariance",
                                              Qos::sensor(4));
    hand_in_eye_ = ctx.param_choice("hand_frame", "base",
                                    "the hand position's frame: base (none until eye_T_base has come: what the "
                                    "display's readers take) or eye (the camera's, always)",
                                    {"base", "eye"}) == "eye";
    hand_sigma_ = ctx.param<double>(
        "hand_sigma", 0.05,
        "m: the hand point's standard deviation as the fingertip's (the visible surface's centre is on the palm, "
        "10-15 cm behind a pointing fingertip: 3 sigma covers that)",
        Range{0.001, 1});
    if (!(box[0] < box[1] && box[2] < box[3] && box[4] < box[5]))
      ctx.reject("device_box", "each min must be below its max");
    if (!(s.min_depth < s.max_depth)) ctx.reject("max_depth", "must be larger than min_depth");
    if (s.block_size % 2 == 0 || (s.algorithm == "bm" && s.block_size < 5))
      ctx.reject("block_size", "expected an odd number (at least 5 with algorithm bm)");
    if (s.num_disparities % 16 != 0)
      ctx.reject("num_disparities", "expected 0 (from the depth range) or a multiple of 16");
    hand_.device_box =
        Eigen::AlignedBox3d(Eigen::Vector3d(box[0], box[2], box[4]), Eigen::Vector3d(box[1], box[3], box[5]));
    if (ctx.issues().empty()) matcher_.emplace(s);
  }

  void tick(Time now) override {
    read_poses();
    pair_.read_calibration(complaints_);
    if (pair_.next_pair(complaints_)) compute_depth(now);
    if (keyed_in_.take_latest(keyed_)) keyed_pending_ = true;
    // The keyed frame may arrive before or after its stereo pair: use it once both are there.
    if (keyed_pending_ && depth_stamp_ >= 0 && keyed_.header().stamp_ns() == depth_stamp_) {
      keyed_pending_ = false;
      locate_hand(now);
    }
  }

 private:
  // The camera pose and the plate pose, when connected.
  void read_poses() {
    while (take_checked(eye_T_base_in_, pose_))
      base_T_eye_ = msgs::to_isometry(pose_.pose()).inverse(), have_pose_ = true;
    while (take_checked(eye_T_dev_in_, pose_)) dev_T_eye_ = msgs::to_isometry(pose_.pose()).inverse(), have_dev_ = true;
  }

  void compute_depth(Time now) {
    const msg::Image& left_image = pair_.left();
    const bool mono = std::string_view(left_image.encoding().c_str()) == "mono8";
    const cv::Mat left = image::view(left_image), right = image::view(pair_.right());
    if (mono) {
      left_grey_ = left, right_grey_ = right;
    } else {
      cv::cvtColor(left, left_grey_, cv::COLOR_RGB2GRAY);
      cv::cvtColor(right, right_grey_, cv::COLOR_RGB2GRAY);
    }
    matcher_->compute(left_grey_, right_grey_, pair_.intrinsics().fx, pair_.baseline(), depth_);
    depth_stamp_ = left_image.header().stamp_ns();
    cv::Mat pixels = image::allocate(depth_msg_, depth_.cols, depth_.rows, "32FC1");
    depth_.copyTo(pixels);
    fill_header(depth_msg_.header(), depth_stamp_ ? depth_stamp_ : now.ns, left_image.header().seq(), "eye");
    depth_out_.write(depth_msg_);
  }

  void locate_hand(Time now) {
    if (const std::string bad = image::problem(keyed_, {"rgba8"}, static_cast<std::uint32_t>(depth_.cols),
                                               static_cast<std::uint32_t>(depth_.rows));
        !bad.empty()) {
      reject(keyed_in_, bad + " (the stereo pair's); no hand position for this frame");
      return;
    }
    cv::extractChannel(image::view(keyed_), alpha_, 3);
    const msgs::CameraIntrinsics& K = pair_.intrinsics();
    const auto hand = estimate_hand_point(depth_, alpha_, Intrinsics{K.fx, K.fy, K.cx, K.cy}, hand_,
                                          have_dev_ ? &dev_T_eye_ : nullptr, points_);
    if (!hand) return;                         // no hand in view (or too little of it with depth)
    if (!hand_in_eye_ && !have_pose_) return;  // (base: not before the camera's pose is known)
    fill_header(hand_msg_.header(), depth_stamp_ ? depth_stamp_ : now.ns, keyed_.header().seq(),
                hand_in_eye_ ? "eye" : "base");
    const Eigen::Vector3d p = hand_in_eye_ ? hand->eye_p_hand : Eigen::Vector3d(base_T_eye_ * hand->eye_p_hand);
    msgs::to_msg(p, hand_msg_.position());
    for (std::size_t i = 0; i < 9; ++i) hand_msg_.covariance()[i] = i % 4 == 0 ? hand_sigma_ * hand_sigma_ : 0.0;
    hand_msg_.status(msg::TRACKING_OK);
    hand_msg_.source("stereo");
    hand_out_.write(hand_msg_);
  }

  std::optional<DisparityDepth> matcher_;
  HandPointOptions hand_;
  StereoIntake pair_;
  const StereoIntake::Complaints complaints_{
      [this](const Input<msg::Image>& in, const std::string& why) { reject(in, why); },
      [this](const Input<msg::CameraInfo>& in, const std::string& why) { reject(in, why); },
      [this](const std::string& what) { warn_once(what); }};
  double hand_sigma_ = 0.04;
  std::int64_t depth_stamp_ = -1;
  Eigen::Isometry3d base_T_eye_ = Eigen::Isometry3d::Identity(), dev_T_eye_ = Eigen::Isometry3d::Identity();
  bool have_pose_ = false, have_dev_ = false, keyed_pending_ = false, hand_in_eye_ = false;
  cv::Mat left_grey_, right_grey_, depth_, alpha_;
  std::vector<Eigen::Vector3f> points_;
  msg::Image keyed_, depth_msg_;
  msg::PoseStamped pose_;
  msg::HandPosition hand_msg_;
  Input<msg::Image> keyed_in_;
  Input<msg::PoseStamped> eye_T_base_in_, eye_T_dev_in_;
  Output<msg::Image> depth_out_;
  Output<msg::HandPosition> hand_out_;
};

}  // namespace wysiwyf::vision

WYSIWYF_COMPONENT(wysiwyf::vision::StereoDepth, "stereo_depth")
