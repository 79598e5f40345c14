#include "stereo_intake.hpp"

#include <cstdlib>

#include "image/image_view.hpp"

namespace wysiwyf::vision {

namespace {
std::string size_text(std::uint32_t width, std::uint32_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}
}  // namespace

void StereoIntake::configure(Context& ctx, std::initializer_list<std::string_view> encodings) {
  encodings_.assign(encodings.begin(), encodings.end());
  baseline_param_ = ctx.param<double>(
      "baseline", 0.0, "the right camera along +x of the left, m (0: from right_camera_info)", Range{0, 2});
  max_skew_ns_ = static_cast<std::int64_t>(
      ctx.param<double>("max_skew_ms", 5.0, "left and right frames further apart in time are not paired, ms",
                        Range{0, 1000}) *
      1e6);
  std::string accepted;
  for (const auto e : encodings_) accepted += (accepted.empty() ? "" : ", ") + std::string(e);
  left_in_ = ctx.input<msg::Image>("left", "left (reference) image, rectified: " + accepted, Qos::sensor(2));
  right_in_ = ctx.input<msg::Image>("right",
                                    "right image, rectified, displaced along +x of the left, same encoding "
                                    "and size",
                                    Qos::sensor(2));
  info_in_ = ctx.input<msg::CameraInfo>("camera_info", "the left camera's intrinsics (K)", Qos::sensor(2));
  right_info_in_ = ctx.input<msg::CameraInfo>("right_camera_info",
                                              "optional: the right camera's P gives the baseline (P[3] = -fx B)",
                                              Qos::sensor(2).optional_input());
}

void StereoIntake::read_calibration(const Complaints& complain) {
  while (info_in_.take(info_)) {
    if (const auto K = msgs::intrinsics(info_))
      K_ = *K;
    else
      complain.reject_info(info_in_, "no focal length (expected K[0], K[4] > 0)");
  }
  while (right_info_in_.take(right_info_)) {
    if (const auto baseline = msgs::stereo_baseline(right_info_))
      info_baseline_ = *baseline;
    else
      complain.reject_info(right_info_in_, "no baseline (expected P[0] > 0 and P[3] = -fx B < 0)");
  }
}

bool StereoIntake::next_pair(const Complaints& complain) {
  left_fresh_ |= left_in_.take_latest(left_);
  right_fresh_ |= right_in_.take_latest(right_);
  if (!left_fresh_ || !right_fresh_) return false;  // wait for the partner
  const std::int64_t skew = elapsed_ns(left_.header().stamp_ns(), right_.header().stamp_ns());
  if (std::abs(skew) > max_skew_ns_) {  // not one exposure: drop the older side, wait for its partner
    (skew > 0 ? right_fresh_ : left_fresh_) = false;
    return false;
  }
  left_fresh_ = right_fresh_ = false;
  std::string bad = image::problem(left_, encodings_);
  if (!bad.empty()) {
    complain.reject_image(left_in_, bad);
    return false;
  }
  bad = image::problem(right_, {left_.encoding().c_str()}, left_.width(), left_.height());
  if (!bad.empty()) {
    complain.reject_image(right_in_, bad + " (a rectified pair has one encoding and size)");
    return false;
  }
  std::string missing;
  if (K_.fx <= 0)
    missing = "no intrinsics yet (camera_info)";
  else if (K_.width != static_cast<int>(left_.width()) || K_.height != static_cast<int>(left_.height()))
    missing = "camera_info is for " + size_text(K_.width, K_.height) + " but the images are " +
              size_text(left_.width(), left_.height());
  else if (baseline() <= 0)
    missing = "no baseline: set the baseline parameter or connect right_camera_info";
  if (!missing.empty()) {
    complain.warn_once(missing + "; stereo pairs are skipped until it comes");
    return false;
  }
  return true;
}

}  // namespace wysiwyf::vision
