// device_mask against camera_sim: every pixel the keyer keeps of the real device (the plate's
// knob and lamps, an aluminium plate) lies inside the device's rendered depth, so the compositor
// can keep the device out of what the user sees; and the mask follows the joints and the camera.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "puma_model/puma_model.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::render {

namespace {

cv::Mat view(msg::Image& img, int type) {
  return cv::Mat(static_cast<int>(img.height()), static_cast<int>(img.width()), type, img.data().data());
}

}  // namespace

TEST(DeviceMask, CoversEveryKeyedPixelOfTheRealDevice) {
  const robot::PumaModel model(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "flange");
  // The display demo's camera; the plate on the cube's +x face, then turned and moved.
  Harness cam("camera_sim", "{eye: [1.6, -0.35, 0.7], look_at: [0.75, 0.0, 0.15], noise: 2, seed: 5, plate: aluminium}",
              25);
  Harness keyer("chroma_keyer", "{min_luma: 45}", 25);
  Harness mask("device_mask", "{}", 25);
  auto joints = cam.feed<msg::JointState>("joint_state");
  auto image = cam.watch<msg::Image>("image");
  auto info = cam.watch<msg::CameraInfo>("camera_info");
  auto eye_T_base = cam.watch<msg::PoseStamped>("true_eye_T_base");
  auto true_device = cam.watch<msg::Image>("true_device_mask");
  auto key_in = keyer.feed<msg::Image>("image");
  auto hand = keyer.watch<msg::Image>("hand");
  auto mask_joints = mask.feed<msg::JointState>("joint_state");
  auto mask_pose = mask.feed<msg::PoseStamped>("eye_T_base");
  auto mask_info = mask.feed<msg::CameraInfo>("camera_info");
  auto depth = mask.watch<msg::Image>("depth");
  cam.activate();
  keyer.activate();
  mask.activate();
  const robot::Vector6d poses[] = {
      (robot::Vector6d() << 0.255486, -0.429048, -2.231546, 0.286487, 1.106586, 3.010371).finished(),
      (robot::Vector6d() << 0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254).finished(),
      (robot::Vector6d() << 0.1, -0.3, -2.4, 0.5, 1.0, 2.6).finished()};
  int k = 0;
  for (const auto& q : poses) {
    const Time t{k * 40'000'000LL};
    msg::JointState js;
    fill_header(js.header(), t.ns, static_cast<std::uint64_t>(k), "base");
    js.position().resize(6);
    for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = q[i];
    joints.write(js);
    cam.tick(t);
    msg::Image img, keyed, dev, truth;
    msg::CameraInfo ci;
    msg::PoseStamped pose;
    ASSERT_TRUE(image.take_latest(img) && info.take_latest(ci) && eye_T_base.take_latest(pose) &&
                true_device.take_latest(truth));
    key_in.write(img);
    keyer.tick(t);
    ASSERT_TRUE(hand.take_latest(keyed));
    mask_info.write(ci);
    mask_joints.write(js);
    mask_pose.write(pose);
    mask.tick(t);
    ASSERT_TRUE(depth.take_latest(dev)) << "pose " << k;
    ASSERT_EQ(dev.encoding(), "32FC1");
    std::vector<cv::Mat> rgba;
    cv::split(view(keyed, CV_8UC4), rgba);
    const cv::Mat device = view(dev, CV_32FC1) > 0.0f, kept = rgba[3] > 127;
    const int keyed_device = cv::countNonZero(kept), outside = cv::countNonZero(kept & ~device);
    std::printf("[measured] pose %d: %d keyed pixels of the device, %d outside the mask; the mask %d px\n", k,
                keyed_device, outside, cv::countNonZero(device));
    EXPECT_GT(keyed_device, 50) << "the knob and the plate are seen and keyed";
    EXPECT_EQ(outside, 0) << "pose " << k;
    // camera_sim's own truth of where the device is seen lies inside it too, and is most of it.
    const cv::Mat seen = view(truth, CV_8UC1) > 127;
    EXPECT_EQ(cv::countNonZero(seen & ~device), 0) << "pose " << k;
    EXPECT_GT(cv::countNonZero(seen), cv::countNonZero(device) / 2) << "pose " << k;
    // Its depth is the device's: within a few cm of the plate's distance from the camera.
    const Eigen::Isometry3d eye_T_dev = msgs::to_isometry(pose.pose()) * model.fk(q, model.frame("dev"));
    double lo = 0, hi = 0;
    cv::minMaxLoc(view(dev, CV_32FC1), &lo, &hi, nullptr, nullptr, device);
    EXPECT_LT(lo, eye_T_dev.translation().z() + 0.01);
    EXPECT_GT(hi, eye_T_dev.translation().z());
    ++k;
  }
}

}  // namespace wysiwyf::render
