#pragma once
// Metric depth from a rectified grey stereo pair: OpenCV block matching (StereoBM) or
// semi-global matching (StereoSGBM) on optionally downscaled images, disparity -> depth
// Z = fx B / d, restricted to a depth range. The disparity search range follows from that depth
// range, the focal length and the baseline unless it is given.
#include <opencv2/calib3d.hpp>

#include <string>

namespace wysiwyf::vision {

struct StereoSettings {
  std::string algorithm = "sgbm";           // "bm", "sgbm" (5 paths) or "sgbm_3way"
  int num_disparities = 0;                  // at the matched resolution; 0: from min_depth and max_depth
  int block_size = 5;                       // odd
  int downscale = 2;                        // match on images this many times smaller
  double min_depth = 0.3, max_depth = 3.0;  // m
  int uniqueness_ratio = 10;                // percent by which the best match must beat the second
  int speckle_window = 100;  // px at the matched resolution: smaller disparity blobs are dropped (0: keep)
};

class DisparityDepth {
 public:
  explicit DisparityDepth(StereoSettings settings);

  // left, right: CV_8UC1, same size, rectified (right camera displaced along +x of the left).
  // fx: the left camera's focal length in px at this size; baseline in m.
  // depth: CV_32FC1 of the same size, metres, 0 where unknown or outside [min_depth, max_depth].
  void compute(const cv::Mat& left, const cv::Mat& right, double fx, double baseline, cv::Mat& depth);

  int min_disparity() const { return min_disparity_; }
  int num_disparities() const { return num_disparities_; }

 private:
  void prepare(double fx_matched, double baseline);

  StereoSettings s_;
  cv::Ptr<cv::StereoMatcher> matcher_;
  double prepared_for_ = -1;  // fx_matched * baseline the matcher's range was set for
  int min_disparity_ = 0, num_disparities_ = 16;
  cv::Mat small_left_, small_right_, padded_left_, padded_right_, padded_disparity_, disparity_f_, small_depth_,
      invalid_;
};

}  // namespace wysiwyf::vision
