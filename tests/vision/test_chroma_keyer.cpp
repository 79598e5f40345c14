// The chroma keyer against camera_sim's ground truth: the hand over blue cloth, with noise, blur,
// lighting variation and blue spill on the hand's edges.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::vision {

TEST(ChromaKeyer, MatchesTheTrueHandMask) {
  Harness cam("camera_sim", "{noise: 2.0, spill: 0.3, seed: 5}", 25);
  auto hand_in = cam.feed<msg::PoseStamped>("hand_pose");
  auto image = cam.watch<msg::Image>("image");
  auto truth = cam.watch<msg::Image>("true_hand_mask");
  cam.activate();
  Harness keyer("chroma_keyer", "{}", 25);
  auto frames = keyer.feed<msg::Image>("image");
  auto matte = keyer.watch<msg::Image>("matte");
  auto hand = keyer.watch<msg::Image>("hand");
  keyer.activate();
  double worst_iou = 1, worst_mae = 0;
  int frame = 0;
  // The hand at several places and angles in front of the cloth (no arm: the plate is not blue
  // and would be keyed in too; the truth here is the hand alone).
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
      cam.tick(Time{frame * 40'000'000LL});
      msg::Image img, mask;
      ASSERT_TRUE(image.take_latest(img));
      ASSERT_TRUE(truth.take_latest(mask));
      frames.write(img);
      keyer.tick(Time{frame * 40'000'000LL});
      msg::Image a;
      ASSERT_TRUE(matte.take_latest(a));
      const cv::Mat alpha(static_cast<int>(a.height()), static_cast<int>(a.width()), CV_8UC1, a.data().data());
      const cv::Mat gt(static_cast<int>(mask.height()), static_cast<int>(mask.width()), CV_8UC1, mask.data().data());
      ASSERT_GT(cv::countNonZero(gt), 1000) << "the hand is not in view";
      const cv::Mat keyed = alpha > 127;
      const double iou = static_cast<double>(cv::countNonZero(keyed & gt)) / cv::countNonZero(keyed | gt);
      cv::Mat diff;
      cv::absdiff(alpha, gt, diff);
      const double mae = cv::mean(diff)[0] / 255.0;
      worst_iou = std::min(worst_iou, iou);
      worst_mae = std::max(worst_mae, mae);
      ++frame;
    }
  std::cout << "worst IoU " << worst_iou << ", worst alpha MAE " << worst_mae << " over " << frame << " frames\n";
  EXPECT_GE(worst_iou, 0.97);
  EXPECT_LE(worst_mae, 0.03);
  msg::Image h;
  ASSERT_TRUE(hand.take_latest(h));
  EXPECT_EQ(std::string(h.encoding().c_str()), "rgba8");
}

TEST(ChromaKeyer, SuppressesBlueSpillOnWhatItKeeps) {
  Harness keyer("chroma_keyer", "{}", 25);
  auto frames = keyer.feed<msg::Image>("image");
  auto hand = keyer.watch<msg::Image>("hand");
  keyer.activate();
  msg::Image img;
  img.width(2), img.height(1), img.encoding("rgb8"), img.step(6);
  img.data() = {200, 150, 120,   // skin: kept, untouched
                180, 130, 190};  // skin with blue spill: kept, blue limited to max(red, green)
  frames.write(img);
  keyer.tick(Time{0});
  msg::Image out;
  ASSERT_TRUE(hand.take_latest(out));
  ASSERT_EQ(out.data().size(), 8u);
  EXPECT_EQ(out.data()[3], 255);  // opaque
  EXPECT_EQ((std::vector<int>{out.data()[0], out.data()[1], out.data()[2]}), (std::vector<int>{200, 150, 120}));
  EXPECT_EQ(out.data()[7], 255);
  EXPECT_EQ(out.data()[6], 180);  // blue 190 -> 180
}

}  // namespace wysiwyf::vision
