#pragma once
// A short stereo recording for the real-hardware pipelines' tests (demo-real*.yaml), made by
// camera_sim: 2 s at 25 Hz of the arm parked at `parked` and a hand with the fingertip LED coming
// in from 1.1 m to 0.85 m, pointing along -x, as left_K.png / right_K.png (K = 0..49) in `dir`,
// which the camera component reads as an image sequence (source: dir/left_%d.png).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {

// urdf: the arm camera_sim draws (blue-wrapped, with its plate, lamps and knob).
inline void write_stereo_recording(const std::filesystem::path& dir, const std::string& urdf,
                                   const Eigen::Matrix<double, 6, 1>& parked) {
  Harness cam("camera_sim",
              "{eye: [1.6, -0.35, 0.7], look_at: [0.75, 0.0, 0.15], stereo_baseline: 0.06, fingertip_marker: true, "
              "plate: cloth, urdf: " +
                  urdf + "}",
              25);
  auto joints = cam.feed<msg::JointState>("joint_state");
  auto hand = cam.feed<msg::PoseStamped>("hand_pose");
  auto left = cam.watch<msg::Image>("image"), right = cam.watch<msg::Image>("image_right");
  cam.activate();
  msg::JointState js;
  js.position().resize(6);
  for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = parked[i];
  for (int k = 0; k < 50; ++k) {
    joints.write(js);
    Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();
    tip.linear() << -1, 0, 0, 0, -1, 0, 0, 0, 1;  // pointing along -x, the back of the hand up
    tip.translation() =
        Eigen::Vector3d(1.1 - 0.25 * std::min(1.0, k / 40.0), 0.0, 0.2 - 0.08 * std::min(1.0, k / 40.0));
    msg::PoseStamped p;
    msgs::to_msg(tip, p.pose());
    hand.write(p);
    cam.tick(Time{k * 40'000'000LL});
    msg::Image l, r;
    ASSERT_TRUE(left.take_latest(l) && right.take_latest(r));
    for (auto [img, side] : {std::pair{&l, "left"}, std::pair{&r, "right"}}) {
      cv::Mat bgr;
      cv::cvtColor(
          cv::Mat(static_cast<int>(img->height()), static_cast<int>(img->width()), CV_8UC3, img->data().data()), bgr,
          cv::COLOR_RGB2BGR);
      cv::imwrite((dir / (std::string(side) + "_" + std::to_string(k) + ".png")).string(), bgr);
    }
  }
}

}  // namespace wysiwyf::test
