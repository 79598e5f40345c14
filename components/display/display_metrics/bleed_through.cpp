#include "bleed_through.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "image/image_view.hpp"
#include "summary_json.hpp"

namespace wysiwyf::display {

void BleedThrough::add_device_mask(msg::Image&& mask) {
  device_masks_.push_back(std::move(mask));
  if (device_masks_.size() > kMasksKept) device_masks_.pop_front();
}

void BleedThrough::measure(const msg::Image& shown) {
  const auto mask = std::find_if(device_masks_.begin(), device_masks_.end(), [&](const msg::Image& m) {
    return m.header().stamp_ns() == shown.header().stamp_ns();
  });
  if (mask == device_masks_.end() || mask->width() != shown.width() || mask->height() != shown.height())
    return;  // its frame's truth is gone or never came
  // The device's own pixels, not its outline: at an edge the image's blur and the keyer's soft
  // matte mix it with what is next to it (the hand over it, the cloth around it).
  cv::erode(vision::image::view(*mask), inner_, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
  cv::Mat seen = vision::image::view(shown) > 127;
  seen &= inner_;
  const int bleed = cv::countNonZero(seen);
  px_.add(bleed, shown.header().stamp_ns());
  images_with_any_ += bleed > 0 ? 1 : 0;
}

std::string BleedThrough::end_line() const {
  if (px_.samples() == 0) return "";
  return "bleed-through (real device pixels the user sees) over " + std::to_string(px_.samples()) +
         " images: " + std::to_string(images_with_any_) + " with any, p99 " + std::to_string(px_.percentile(99)) +
         " px, max " + std::to_string(px_.max()) + " px";
}

void BleedThrough::write_json(std::ostream& j) const {
  j << "\"bleed_through\": {\"images\": " << px_.samples() << ", \"images_with_any\": " << images_with_any_
    << ", \"p99_px\": " << json_number(px_.percentile(99)) << ", \"max_px\": " << json_number(px_.max()) << "}";
}

}  // namespace wysiwyf::display
