#pragma once
// The frames both chroma keyers are measured on: camera_sim's hand over the blue cloth (noise,
// blur, spill; the chroma keyer test's nine hand poses) with camera_sim's true hand mask, and the
// score of a matte against that mask.
#include <opencv2/core.hpp>

#include <vector>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::vision {

struct KeyerFrame {
  msg::Image image;  // rgb8, as the keyer receives it
  cv::Mat rgb;       // the same pixels
  cv::Mat truth;     // mono8, 255 where the hand is
};

inline const std::vector<KeyerFrame>& keyer_frames() {
  static const std::vector<KeyerFrame> frames = [] {
    Harness cam("camera_sim", "{noise: 2.0, spill: 0.3, seed: 5}", 25);
    auto hand_in = cam.feed<msg::PoseStamped>("hand_pose");
    auto image = cam.watch<msg::Image>("image");
    auto truth = cam.watch<msg::Image>("true_hand_mask");
    cam.activate();
    std::vector<KeyerFrame> out;
    for (double x : {0.55, 0.7, 0.85})
      for (double angle : {0.0, 0.8, -1.2}) {
        Eigen::Isometry3d base_T_hand = Eigen::Isometry3d::Identity();
        base_T_hand.linear() =
            (Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitX()))
                .toRotationMatrix();
        base_T_hand.translation() = Eigen::Vector3d(x, -0.05, 0.35);
        msg::PoseStamped p;
        msgs::to_msg(base_T_hand, p.pose());
        hand_in.write(p);
        cam.tick(Time{static_cast<std::int64_t>(out.size()) * 40'000'000});
        KeyerFrame f;
        msg::Image mask;
        image.take_latest(f.image);
        truth.take_latest(mask);
        const int h = static_cast<int>(f.image.height()), w = static_cast<int>(f.image.width());
        f.rgb = cv::Mat(h, w, CV_8UC3, f.image.data().data()).clone();
        f.truth = cv::Mat(h, w, CV_8UC1, mask.data().data()).clone();
        out.push_back(std::move(f));
      }
    return out;
  }();
  return frames;
}

struct MatteScore {
  double iou = 0, mae = 0;  // IoU of alpha > 127 with the mask; mean |alpha - mask| on 0..1
};

inline MatteScore score(const cv::Mat& alpha, const cv::Mat& truth) {
  const cv::Mat keyed = alpha > 127;
  cv::Mat diff;
  cv::absdiff(alpha, truth, diff);
  return {static_cast<double>(cv::countNonZero(keyed & truth)) / cv::countNonZero(keyed | truth),
          cv::mean(diff)[0] / 255.0};
}

}  // namespace wysiwyf::vision
