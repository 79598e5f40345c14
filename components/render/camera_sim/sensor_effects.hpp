#pragma once
// What a real camera does to the light that reaches it, applied to a rendered image: the
// lighting's gain, blue spill from the cloth on the hand's outer edge, optical blur and sensor
// noise (Gaussian, seeded: a run is reproducible).
#include <cstdint>

#include <opencv2/core.hpp>

namespace wysiwyf::render {

struct SensorEffectsParams {
  double noise = 2;    // grey levels, sigma
  double blur = 0.7;   // px, sigma (0: none)
  double spill = 0.3;  // 0..1 of the cloth's colour on the hand's outer 2 px
  cv::Scalar cloth;    // the cloth's colour, 0..255 per channel
};

class SensorEffects {
 public:
  SensorEffects() = default;
  SensorEffects(const SensorEffectsParams& params, std::uint64_t seed) : p_(params), rng_(seed) {}

  // img (CV_8UC3) in place: times gain, spill where `hand_mask` (CV_8UC1; empty: none) has its
  // edge, blurred, noise added, saturated back to 8 bits.
  void apply(cv::Mat& img, const cv::Mat& hand_mask, double gain);
  const SensorEffectsParams& params() const { return p_; }

 private:
  SensorEffectsParams p_;
  cv::RNG rng_;
  cv::Mat work_, noise_, inner_, tinted_;  // reused between images
};

}  // namespace wysiwyf::render
