#include "disparity_depth.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <stdexcept>

namespace wysiwyf::vision {

DisparityDepth::DisparityDepth(StereoSettings settings) : s_(std::move(settings)) {
  if (s_.algorithm != "bm" && s_.algorithm != "sgbm" && s_.algorithm != "sgbm_3way")
    throw std::invalid_argument("stereo algorithm '" + s_.algorithm + "': expected bm, sgbm or sgbm_3way");
  if (s_.block_size % 2 == 0 || s_.block_size < (s_.algorithm == "bm" ? 5 : 1))
    throw std::invalid_argument("block_size " + std::to_string(s_.block_size) +
                                ": expected an odd number (at least 5 for bm)");
  if (s_.num_disparities % 16 != 0 || s_.num_disparities < 0)
    throw std::invalid_argument("num_disparities " + std::to_string(s_.num_disparities) +
                                ": expected 0 (from the depth range) or a multiple of 16");
  if (!(s_.min_depth > 0) || !(s_.max_depth > s_.min_depth))
    throw std::invalid_argument("depth range: expected 0 < min_depth < max_depth");
  if (s_.downscale < 1) throw std::invalid_argument("downscale: expected 1 or more");
}

void DisparityDepth::prepare(double fx_matched, double baseline) {
  const double fb = fx_matched * baseline;  // disparity (px) times depth (m)
  if (matcher_ && fb == prepared_for_) return;
  min_disparity_ = static_cast<int>(std::floor(fb / s_.max_depth));
  num_disparities_ = s_.num_disparities;
  if (num_disparities_ == 0) {
    const int max_disparity = static_cast<int>(std::ceil(fb / s_.min_depth));
    num_disparities_ = std::max(16, (max_disparity - min_disparity_ + 1 + 15) / 16 * 16);
  }
  constexpr int kSpeckleRangePx = 2;  // disparity spread inside one connected blob
  if (s_.algorithm == "bm") {
    auto bm = cv::StereoBM::create(num_disparities_, s_.block_size);
    bm->setMinDisparity(min_disparity_);
    bm->setUniquenessRatio(s_.uniqueness_ratio);
    bm->setSpeckleWindowSize(s_.speckle_window);
    bm->setSpeckleRange(kSpeckleRangePx * cv::StereoMatcher::DISP_SCALE);  // BM compares in 1/16 px
    matcher_ = bm;
  } else {
    const int area = s_.block_size * s_.block_size;  // P1, P2: OpenCV's recommended smoothness for one channel
    matcher_ = cv::StereoSGBM::create(
        min_disparity_, num_disparities_, s_.block_size, 8 * area, 32 * area,
        /*disp12MaxDiff=*/1, /*preFilterCap=*/31, s_.uniqueness_ratio, s_.speckle_window, kSpeckleRangePx,
        s_.algorithm == "sgbm" ? cv::StereoSGBM::MODE_SGBM : cv::StereoSGBM::MODE_SGBM_3WAY);
  }
  prepared_for_ = fb;
}

void DisparityDepth::compute(const cv::Mat& left, const cv::Mat& right, double fx, double baseline, cv::Mat& depth) {
  const cv::Mat* l = &left;
  const cv::Mat* r = &right;
  if (s_.downscale > 1) {
    const cv::Size small(left.cols / s_.downscale, left.rows / s_.downscale);
    cv::resize(left, small_left_, small, 0, 0, cv::INTER_AREA);
    cv::resize(right, small_right_, small, 0, 0, cv::INTER_AREA);
    l = &small_left_, r = &small_right_;
  }
  const double f = fx * l->cols / left.cols;
  prepare(f, baseline);
  // The matchers leave the left image's first min_disparity + num_disparities columns unmatched
  // (their search would leave the right image): a fifth of the width at the demo's range, where a
  // hand waiting at the image's edge was lost. Both images are widened by that much on the left,
  // edge pixels repeated, so each pixel of the image is searched over every disparity that stays
  // inside the right image; one whose match would lie outside it finds only repeated edge pixels,
  // which the uniqueness and left-right checks refuse.
  const int pad = min_disparity_ + num_disparities_;
  cv::copyMakeBorder(*l, padded_left_, 0, 0, pad, 0, cv::BORDER_REPLICATE);
  cv::copyMakeBorder(*r, padded_right_, 0, 0, pad, 0, cv::BORDER_REPLICATE);
  matcher_->compute(padded_left_, padded_right_, padded_disparity_);
  padded_disparity_(cv::Rect(pad, 0, l->cols, l->rows))
      .convertTo(disparity_f_, CV_32F, 1.0 / cv::StereoMatcher::DISP_SCALE);
  cv::Mat& out = s_.downscale > 1 ? small_depth_ : depth;
  cv::divide(f * baseline, disparity_f_, out);  // Z = f B / d (0 where d is 0)
  // Unmatched pixels come back below min_disparity; keep only the configured depth range.
  invalid_ = (disparity_f_ < std::max(min_disparity_, 1)) | (out < s_.min_depth) | (out > s_.max_depth);
  out.setTo(0, invalid_);
  if (s_.downscale > 1) cv::resize(small_depth_, depth, left.size(), 0, 0, cv::INTER_NEAREST);
}

}  // namespace wysiwyf::vision
