#pragma once
// Bleed-through: per image, the pixels of the real device the user sees, from the compositor's
// real-layer alpha (`shown`) against where the device is in the camera image (camera_sim's
// `true_device_mask`) of the same camera frame (equal stamps). The user should see only the
// virtual scene and the hand: a shown alpha over 127 on the device's own pixels is bleed-through.
#include <cstddef>
#include <deque>
#include <ostream>
#include <string>

#include <opencv2/core.hpp>

#include "stats/percentiles.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::display {

class BleedThrough {
 public:
  // A mono8 mask of the device in a camera frame (the last few are kept for their shown alpha).
  void add_device_mask(msg::Image&& mask);
  // A mono8 shown alpha: measured against its frame's mask, if that is still here.
  void measure(const msg::Image& shown);

  // The run's figures, for the log; empty without any image.
  std::string end_line() const;
  // The summary's "bleed_through" member.
  void write_json(std::ostream& j) const;

 private:
  static constexpr std::size_t kMasksKept = 8;
  std::deque<msg::Image> device_masks_;
  cv::Mat inner_;  // the device's own pixels (the mask eroded)
  stats::Percentiles px_;
  std::size_t images_with_any_ = 0;
};

}  // namespace wysiwyf::display
