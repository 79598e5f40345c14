#include "sensor_effects.hpp"

#include <opencv2/imgproc.hpp>

namespace wysiwyf::render {

void SensorEffects::apply(cv::Mat& img, const cv::Mat& hand_mask, double gain) {
  img.convertTo(work_, CV_32FC3, gain);
  if (!hand_mask.empty() && p_.spill > 0) {
    cv::erode(hand_mask, inner_, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
    const cv::Mat edge = hand_mask & ~inner_;  // the hand's outer 2 px
    cv::addWeighted(work_, 1.0 - p_.spill, cv::Mat(work_.size(), CV_32FC3, p_.cloth), p_.spill, 0, tinted_);
    tinted_.copyTo(work_, edge);
  }
  if (p_.blur > 0) cv::GaussianBlur(work_, work_, cv::Size(0, 0), p_.blur);
  if (p_.noise > 0) {
    noise_.create(work_.size(), CV_32FC3);
    rng_.fill(noise_, cv::RNG::NORMAL, 0, p_.noise);
    work_ += noise_;
  }
  work_.convertTo(img, CV_8UC3);  // saturates
}

}  // namespace wysiwyf::render
