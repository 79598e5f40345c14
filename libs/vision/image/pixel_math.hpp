#pragma once
// round(a b / 255) for 8-bit channel values, exactly (Blinn's trick: v = a b + 128, then
// (v + (v >> 8)) >> 8), one value at a time and 16 at a time with OpenCV's universal intrinsics:
// premultiplying by an alpha (the keyer) and blending under one (the compositor).
#include <cstdint>

#include <opencv2/core/hal/intrin.hpp>

namespace wysiwyf::vision::image {

inline unsigned mul_div255(unsigned a, unsigned b) {
  const unsigned v = a * b + 128u;
  return (v + (v >> 8)) >> 8;
}

#if CV_SIMD128
inline cv::v_uint8x16 mul_div255(const cv::v_uint8x16& a, const cv::v_uint8x16& b) {
  const cv::v_uint16x8 half = cv::v_setall_u16(128);
  cv::v_uint16x8 a0, a1, b0, b1;
  cv::v_expand(a, a0, a1);
  cv::v_expand(b, b0, b1);
  const cv::v_uint16x8 v0 = cv::v_mul_wrap(a0, b0) + half,
                       v1 = cv::v_mul_wrap(a1, b1) + half;  // (at most 255 * 255 + 128)
  return cv::v_pack((v0 + (v0 >> 8)) >> 8, (v1 + (v1 >> 8)) >> 8);
}
#endif

}  // namespace wysiwyf::vision::image
