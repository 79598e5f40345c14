#pragma once
// The input side of a rectified stereo pair, read the same way by every stereo component: the
// left (reference) and right images, paired when they are one exposure (stamps within
// max_skew_ms), one encoding and one size; the left camera's intrinsics (camera_info: K, for the
// images' size); the baseline B from the `baseline` parameter, or else from the right camera's P
// (right_camera_info: P[3] = -fx B). Bad samples are rejected through the component; a pair that
// cannot be used yet (no intrinsics, no baseline) is skipped with one warning saying what is
// missing.
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "wysiwyf/camera_info.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision {

class StereoIntake {
 public:
  // What the component does with a sample it cannot use, or with a pair it must skip.
  struct Complaints {
    std::function<void(const Input<msg::Image>&, const std::string&)> reject_image;
    std::function<void(const Input<msg::CameraInfo>&, const std::string&)> reject_info;
    std::function<void(const std::string&)> warn_once;
  };

  // Declares the parameters `baseline` and `max_skew_ms` and the inputs left, right, camera_info
  // and right_camera_info (optional); `encodings` are the left image's accepted encodings.
  void configure(Context& ctx, std::initializer_list<std::string_view> encodings);

  // Reads the calibration that came since the last call.
  void read_calibration(const Complaints& complain);
  // Reads the images that came; true when a new usable pair is in left() and right().
  bool next_pair(const Complaints& complain);

  const msg::Image& left() const { return left_; }
  const msg::Image& right() const { return right_; }
  // The left camera's intrinsics (fx 0 until camera_info came).
  const msgs::CameraIntrinsics& intrinsics() const { return K_; }
  // The baseline, m: the parameter when set, else the right camera's P; 0 when neither.
  double baseline() const { return baseline_param_ > 0 ? baseline_param_ : info_baseline_; }

 private:
  std::vector<std::string_view> encodings_;
  double baseline_param_ = 0, info_baseline_ = 0;
  std::int64_t max_skew_ns_ = 0;
  bool left_fresh_ = false, right_fresh_ = false;
  msgs::CameraIntrinsics K_;
  msg::Image left_, right_;
  msg::CameraInfo info_, right_info_;
  Input<msg::Image> left_in_, right_in_;
  Input<msg::CameraInfo> info_in_, right_info_in_;
};

}  // namespace wysiwyf::vision
