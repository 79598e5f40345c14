#pragma once
// The real-hardware pipelines (demo-real*.yaml) in tests, against their emulators: a short stereo
// recording for their cameras, made by camera_sim, and a 2 s run of the pipeline on the sim
// clock with the loop recorder beside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "demo_runs.hpp"
#include "display_support.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {

// 2 s at 25 Hz of the arm parked at `parked` and a hand with the fingertip LED coming in from
// 1.1 m to 0.85 m, pointing along -x, as left_K.png / right_K.png (K = 0..49) in `dir`, which the
// camera component reads as an image sequence (source: dir/left_%d.png). urdf: the arm camera_sim
// draws (blue-wrapped, with its plate, lamps and knob).
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

// What a run of a real pipeline showed: its log, and from the loop recorder the ms with a
// tracked hand and with the +x knob as the planner's target.
struct RealRun {
  bool ok = false;
  std::string log;
  int tracked = 0, planned = 0;
};

// `pipeline` (in config/pipelines) for 2 s on the sim clock on `domain`, with the loop recorder
// beside it, its cameras reading write_stereo_recording()'s images in `dir`, and `overrides`
// (the emulators' addresses and the like).
inline RealRun run_real_pipeline(const std::string& pipeline, const std::filesystem::path& dir, int domain,
                                 std::vector<std::string> overrides) {
  const std::string yaml = "wysiwyf: 1\ninclude: [" + kPipelines + pipeline +
                           "]\ncomponents:\n"
                           "  rec: {type: test_display_recorder, rate: 1000, params: {samples: " +
                           (dir / "samples.csv").string() + ", events: " + (dir / "events.csv").string() +
                           "},\n    topics: {joint_state: robot/joint_state, device_pose: robot/device_pose, "
                           "setpoint: robot/setpoint, mode: display/mode, planner: display/planner, "
                           "wrench: robot/wrench, tracked_hand: hand/position}}\n";
  for (const std::string& o :
       {"domain=" + std::to_string(domain), std::string("dds.transport=local"), std::string("clock.mode=sim"),
        std::string("clock.step=1ms"), std::string("clock.pace=1"), std::string("clock.duration=2s"),
        "camera.params.source=" + (dir / "left_%d.png").string(), std::string("camera.params.backend=any"),
        "camera_right.params.source=" + (dir / "right_%d.png").string(), std::string("camera_right.params.backend=any"),
        "record.params.path=" + (dir / "real.mp4").string()})
    overrides.push_back(o);
  const PipelineSpec spec = load_pipeline_from_string(yaml, (dir / "real-with-recorder.yaml").string(), overrides);
  Loader loader({WYSIWYF_TEST_COMPONENT_DIR, WYSIWYF_COMPONENT_DIR});
  std::ostringstream log;
  RunResult result;
  {
    Runtime runtime(spec, loader, RunOptions{"", false, &log});
    result = runtime.run();
  }
  RealRun run{result.ok, result.ok ? log.str() : result.error + "\n" + log.str()};
  std::ifstream samples(dir / "samples.csv");
  for (std::string row; std::getline(samples, row);) {
    const auto f = split(row);
    if (f.size() < 45) continue;
    run.tracked += std::stoi(f[44]) == msg::TRACKING_OK;
    run.planned += f[40] == "cube +x knob";
  }
  return run;
}

}  // namespace wysiwyf::test
