#pragma once
// What the `camera` component (the pipelines' reader of a calibration file) publishes as its
// camera_info for a calibration file: one black 640 x 480 frame of a folder source, undistort off.
#include <filesystem>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

// False when the component published nothing; `dir` takes the frame.
inline bool camera_info_of(const std::filesystem::path& calibration, const std::filesystem::path& dir,
                           msg::CameraInfo& info) {
  cv::imwrite((dir / "frame_0.png").string(), cv::Mat(480, 640, CV_8UC3, cv::Scalar(0, 0, 0)));
  Harness cam(
      "camera",
      "{source: " + (dir / "frame_%d.png").string() + ", calibration: " + calibration.string() + ", undistort: false}",
      25);
  auto out = cam.watch<msg::CameraInfo>("camera_info");
  cam.activate();
  cam.tick(Time{0});
  return out.take_latest(info);
}

}  // namespace wysiwyf::test
