// camera_sim: its image against its own ground truth (mask, poses), on llvmpipe.
#include <gtest/gtest.h>

#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "puma_model/puma_model.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::render {

// The arm with the plate at (0.6, 0, 0.5), facing the camera at (1.3, -0.5, 0.75).
robot::Vector6d ready_pose(const robot::PumaModel& model) {
  Eigen::Isometry3d base_T_dev = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d p(0.6, 0, 0.5), eye(1.3, -0.5, 0.75);
  const Eigen::Vector3d z = (eye - p).normalized();
  const Eigen::Vector3d x = Eigen::Vector3d::UnitZ().cross(z).normalized();
  base_T_dev.linear().col(0) = x, base_T_dev.linear().col(1) = z.cross(x), base_T_dev.linear().col(2) = z;
  base_T_dev.translation() = p;
  robot::Vector6d q0;
  q0 << 0, 0.5, -0.5, 0, 0.5, 0;
  const auto r = model.ik_nearest(base_T_dev, q0, model.frame("dev"));
  EXPECT_TRUE(r.ok());
  return r.q;
}

TEST(CameraSim, ItsHandMaskAgreesWithItsImageAndItsPosesWithTheModel) {
  const robot::PumaModel model(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "flange");
  const robot::Vector6d q = ready_pose(model);
  Harness h("camera_sim", "{intrinsics: [600, 600, 319.5, 239.5], look_at: [0.6, 0.0, 0.45], noise: 2, seed: 3}", 30);
  auto joints = h.feed<msg::JointState>("joint_state");
  auto hand = h.feed<msg::PoseStamped>("hand_pose");
  auto image = h.watch<msg::Image>("image");
  auto mask = h.watch<msg::Image>("true_hand_mask");
  auto eye_T_dev = h.watch<msg::PoseStamped>("true_eye_T_dev");
  auto eye_T_base = h.watch<msg::PoseStamped>("true_eye_T_base");
  h.activate();
  msg::JointState js;
  js.position().resize(6);
  for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = q[i];
  joints.write(js);
  // The index fingertip 5 cm in front of the plate, pointing at it.
  Eigen::Isometry3d base_T_hand = model.fk(q, model.frame("dev"));
  base_T_hand.translate(Eigen::Vector3d(0.02, 0.0, 0.05));
  base_T_hand.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  msg::PoseStamped hp;
  msgs::to_msg(base_T_hand, hp.pose());
  hand.write(hp);
  h.tick(Time{0});
  msg::Image img, m;
  ASSERT_TRUE(image.take_latest(img));
  ASSERT_TRUE(mask.take_latest(m));
  const cv::Mat rgb(static_cast<int>(img.height()), static_cast<int>(img.width()), CV_8UC3, img.data().data());
  const cv::Mat hand_mask(static_cast<int>(m.height()), static_cast<int>(m.width()), CV_8UC1, m.data().data());
  if (const char* dump = std::getenv("WYSIWYF_DUMP_DIR")) {
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    cv::imwrite(std::string(dump) + "/camera_sim.png", bgr);
    cv::imwrite(std::string(dump) + "/camera_sim_mask.png", hand_mask);
  }
  const int hand_pixels = cv::countNonZero(hand_mask);
  EXPECT_GT(hand_pixels, 2000);
  // Inside the mask (away from its spilled edge) the image is skin; outside there is no skin.
  cv::Mat inner;
  cv::erode(hand_mask, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(9, 9)));
  const cv::Scalar skin = cv::mean(rgb, inner), rest = cv::mean(rgb, ~hand_mask);
  EXPECT_GT(skin[0], skin[2] + 40) << "red over blue inside the mask";
  EXPECT_LT(rest[0], rest[2]) << "blue dominates outside it";
  cv::Mat hsv;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  cv::Mat skin_like;
  cv::inRange(hsv, cv::Scalar(0, 60, 80), cv::Scalar(25, 255, 255), skin_like);
  const int skin_outside = cv::countNonZero(skin_like & ~hand_mask);
  EXPECT_LT(skin_outside, hand_pixels / 50) << "skin-coloured pixels outside the true mask";
  // Ground-truth poses: eye_T_dev = eye_T_base * base_T_dev (FK).
  msg::PoseStamped a, b;
  ASSERT_TRUE(eye_T_dev.take_latest(a));
  ASSERT_TRUE(eye_T_base.take_latest(b));
  const Eigen::Isometry3d expected = msgs::to_isometry(b.pose()) * model.fk(q, model.frame("dev"));
  EXPECT_LE((msgs::to_isometry(a.pose()).matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-9);
}

// With an exposure, the image is the mean of the instantaneous images at the exposure's sample
// times: a hand sweeping sideways at 1 m/s smears over 16 mm in 16 ms. (No noise, blur, flicker
// or spill: those are applied once per frame and would not average.)
TEST(CameraSim, AnExposureAveragesTheSceneOverItsSampleTimes) {
  const robot::PumaModel model(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "flange");
  const robot::Vector6d q = ready_pose(model);
  const std::string common =
      "intrinsics: [600, 600, 319.5, 239.5], look_at: [0.6, 0.0, 0.45], noise: 0, blur: 0, "
      "light_variation: 0, spill: 0";
  msg::JointState js;
  js.position().resize(6);
  for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = q[i];
  Eigen::Isometry3d start = model.fk(q, model.frame("dev"));
  start.translate(Eigen::Vector3d(-0.05, 0.0, 0.12));
  start.rotate(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()));
  constexpr std::int64_t kMs = 1'000'000, kFrame = 100 * kMs;
  // The hand at time t (ms before the frame: 100 - t), moving 1 m/s along the plate's x.
  auto hand_at = [&](std::int64_t t_ns) {
    Eigen::Isometry3d T = start;
    T.translation() += start.linear().col(0) * (1.0 * static_cast<double>(t_ns - (kFrame - 20 * kMs)) * 1e-9);
    msg::PoseStamped p;
    p.header().stamp_ns(t_ns);
    msgs::to_msg(T, p.pose());
    return p;
  };
  auto grab = [](Input<msg::Image>& in) {
    msg::Image m;
    EXPECT_TRUE(in.take_latest(m));
    return cv::Mat(static_cast<int>(m.height()), static_cast<int>(m.width()), CV_8UC3, m.data().data()).clone();
  };
  // The blurred frame: 16 ms, 8 samples at frame - 15, 13, ..., 1 ms.
  Harness blurred("camera_sim", "{" + common + ", exposure: 0.016, exposure_samples: 8}", 10);
  auto b_joints = blurred.feed<msg::JointState>("joint_state");
  auto b_hand = blurred.feed<msg::PoseStamped>("hand_pose");
  auto b_image = blurred.watch<msg::Image>("image");
  blurred.activate();
  b_joints.write(js);
  for (std::int64_t t = kFrame - 20 * kMs; t <= kFrame; t += kMs) b_hand.write(hand_at(t));
  blurred.tick(Time{kFrame});
  const cv::Mat smeared = grab(b_image);
  // The same scene, instantaneous, at each sample time; and at the frame's time.
  Harness sharp("camera_sim", "{" + common + "}", 10);
  auto s_joints = sharp.feed<msg::JointState>("joint_state");
  auto s_hand = sharp.feed<msg::PoseStamped>("hand_pose");
  auto s_image = sharp.watch<msg::Image>("image");
  sharp.activate();
  s_joints.write(js);
  cv::Mat sum = cv::Mat::zeros(smeared.size(), CV_32FC3);
  for (int k = 0; k < 8; ++k) {
    s_hand.write(hand_at(kFrame - (15 - 2 * k) * kMs));
    sharp.tick(Time{(k + 1) * kMs});
    cv::accumulate(grab(s_image), sum);
  }
  cv::Mat mean;
  sum.convertTo(mean, CV_8UC3, 1.0 / 8);
  s_hand.write(hand_at(kFrame));
  sharp.tick(Time{20 * kMs});
  const cv::Mat last = grab(s_image);
  cv::Mat d_mean, d_last;
  cv::absdiff(smeared, mean, d_mean);
  cv::absdiff(smeared, last, d_last);
  const double worst = cv::norm(d_mean, cv::NORM_INF);
  const int smeared_pixels = cv::countNonZero(d_last.reshape(1) > 20);
  std::printf(
      "[measured] exposure 16 ms, 8 samples: worst difference to the mean of the instantaneous images %.0f "
      "grey levels; %d channel values differ by > 20 from the instantaneous frame\n",
      worst, smeared_pixels);
  EXPECT_LE(worst, 1.0);
  EXPECT_GT(smeared_pixels, 500) << "the moving hand must smear";
}

}  // namespace wysiwyf::render
