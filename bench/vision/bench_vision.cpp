// Vision benchmarks: the chroma keyer on 640x480 camera_sim frames (hand over blue cloth), beside
// FFmpeg's chromakey filter on the same frames; stereo depth on camera_sim's stereo pair.
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include <cstdio>

#include "ffmpeg_chromakey.hpp"
#include "keyer_frames.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "../common/smoke.hpp"

namespace wysiwyf::vision {

// Our keyer through its ports on camera_sim's frames, cycling through them; then (untimed) its
// mean IoU and alpha MAE against the true hand masks of the same frames. opencv_threads 0: OpenCV's
// default (both cores here); 1: one thread, like FFmpeg below.
void run_chroma_keyer(benchmark::State& state, int opencv_threads) {
  const auto& frames = keyer_frames();
  const int threads_before = cv::getNumThreads();
  if (opencv_threads > 0) cv::setNumThreads(opencv_threads);
  Harness keyer("chroma_keyer", "{}", 25);
  auto in = keyer.feed<msg::Image>("image");
  auto hand = keyer.watch<msg::Image>("hand", 2);
  auto matte = keyer.watch<msg::Image>("matte", 2);
  keyer.activate();
  msg::Image out;
  std::int64_t t = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    in.write(frames[i++ % frames.size()].image);
    keyer.tick(Time{t += 40'000'000});
    hand.take_latest(out);
  }
  MatteScore mean;
  for (const auto& f : frames) {
    in.write(f.image);
    keyer.tick(Time{t += 40'000'000});
    matte.take_latest(out);
    const MatteScore s = score(cv::Mat(f.truth.size(), CV_8UC1, out.data().data()), f.truth);
    mean.iou += s.iou / static_cast<double>(frames.size()), mean.mae += s.mae / static_cast<double>(frames.size());
  }
  cv::setNumThreads(threads_before);
  state.counters["Mpixel_per_s"] =
      benchmark::Counter(640.0 * 480.0 * static_cast<double>(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
  state.counters["IoU"] = mean.iou;
  state.counters["MAE"] = mean.mae;
}
void BM_ChromaKeyer_640x480(benchmark::State& state) { run_chroma_keyer(state, 0); }
void BM_ChromaKeyer_640x480_OneThread(benchmark::State& state) { run_chroma_keyer(state, 1); }
BENCHMARK(BM_ChromaKeyer_640x480)->Unit(benchmark::kMillisecond)->MinTime(wysiwyf::bench::min_time(1.0));
BENCHMARK(BM_ChromaKeyer_640x480_OneThread)->Unit(benchmark::kMillisecond)->MinTime(wysiwyf::bench::min_time(1.0));

// FFmpeg's chromakey (libavfilter, one thread) on the same frames, key colour the keyer's default
// (26, 41, 158). Its similarity and blend are the best mean IoU (then MAE) over a grid, found once
// on the converted frames before timing.
struct FfmpegSetting {
  double similarity = 0, blend = 0;
  MatteScore score;
  std::string args() const {
    char text[96];
    std::snprintf(text, sizeof text, "color=0x1A299E:similarity=%.3f:blend=%.3f", similarity, blend);
    return text;
  }
};

std::vector<AVFrame*>& yuva_frames() {  // the frames as FFmpeg converts them for chromakey (kept for the run)
  static std::vector<AVFrame*> frames = [] {
    std::vector<AVFrame*> out;
    for (const auto& f : keyer_frames()) out.push_back(FfmpegChromakey::to_yuva444p(f.rgb));
    return out;
  }();
  return frames;
}

MatteScore ffmpeg_score(FfmpegChromakey& key) {
  MatteScore mean;
  const auto& frames = keyer_frames();
  cv::Mat alpha;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    key.key_yuva(yuva_frames()[i], alpha);
    const MatteScore s = score(alpha, frames[i].truth);
    mean.iou += s.iou / static_cast<double>(frames.size()), mean.mae += s.mae / static_cast<double>(frames.size());
  }
  return mean;
}

const FfmpegSetting& ffmpeg_best_setting() {
  static const FfmpegSetting best = [] {
    FfmpegSetting best;
    for (double similarity = 0.02; similarity < 0.1451; similarity += 0.01)
      for (double blend : {0.0, 0.01, 0.02, 0.03, 0.05, 0.08}) {
        FfmpegSetting s{similarity, blend, {}};
        FfmpegChromakey key(640, 480, s.args(), false);
        s.score = ffmpeg_score(key);
        if (s.score.iou > best.score.iou || (s.score.iou == best.score.iou && s.score.mae < best.score.mae)) best = s;
      }
    return best;
  }();
  return best;
}

void report_ffmpeg(benchmark::State& state, const FfmpegSetting& setting, const MatteScore& score) {
  state.counters["Mpixel_per_s"] =
      benchmark::Counter(640.0 * 480.0 * static_cast<double>(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
  state.counters["IoU"] = score.iou;
  state.counters["MAE"] = score.mae;
  state.SetLabel(setting.args());
}

// The filter alone: frames already in yuva444p (the conversion is the next benchmark's).
void BM_FfmpegChromakey_640x480(benchmark::State& state) {
  const FfmpegSetting& setting = ffmpeg_best_setting();
  FfmpegChromakey key(640, 480, setting.args(), false);
  auto& frames = yuva_frames();
  cv::Mat alpha;
  std::size_t i = 0;
  for (auto _ : state) {
    key.key_yuva(frames[i++ % frames.size()], alpha);
    benchmark::DoNotOptimize(alpha.data);
  }
  report_ffmpeg(state, setting, ffmpeg_score(key));
}
BENCHMARK(BM_FfmpegChromakey_640x480)->Unit(benchmark::kMillisecond)->MinTime(wysiwyf::bench::min_time(1.0));

// What `ffmpeg -vf chromakey` does with RGB frames: swscale to yuva444p, then the filter.
void BM_FfmpegChromakey_640x480_WithConversion(benchmark::State& state) {
  const FfmpegSetting& setting = ffmpeg_best_setting();
  FfmpegChromakey key(640, 480, setting.args(), true);
  const auto& frames = keyer_frames();
  cv::Mat alpha;
  std::size_t i = 0;
  for (auto _ : state) {
    key.key_rgb(frames[i++ % frames.size()].rgb, alpha);
    benchmark::DoNotOptimize(alpha.data);
  }
  MatteScore mean;
  for (const auto& f : frames) {
    key.key_rgb(f.rgb, alpha);
    const MatteScore s = score(alpha, f.truth);
    mean.iou += s.iou / static_cast<double>(frames.size()), mean.mae += s.mae / static_cast<double>(frames.size());
  }
  report_ffmpeg(state, setting, mean);
}
BENCHMARK(BM_FfmpegChromakey_640x480_WithConversion)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(wysiwyf::bench::min_time(1.0));

// stereo_depth on camera_sim's 640x480 stereo pair (6 cm baseline) with the hand 0.6 m from the
// camera, the keyer's output beside it: depth image and hand position per frame, through the ports.
void BM_StereoDepth_640x480(benchmark::State& state, const std::string& params) {
  Harness cam("camera_sim", "{stereo_baseline: 0.06}", 25);
  auto hand_in = cam.feed<msg::PoseStamped>("hand_pose");
  auto image = cam.watch<msg::Image>("image");
  auto image_right = cam.watch<msg::Image>("image_right");
  auto info_out = cam.watch<msg::CameraInfo>("camera_info");
  cam.activate();
  const Eigen::Vector3d eye(1.3, -0.5, 0.75), look_at(0.55, 0.0, 0.35);  // camera_sim's default camera
  const Eigen::Vector3d d = (look_at - eye).normalized();
  Eigen::Isometry3d base_T_hand = Eigen::Isometry3d::Identity();  // palm toward the camera
  base_T_hand.linear().col(2) = -d;
  base_T_hand.linear().col(0) = d.cross(Eigen::Vector3d::UnitZ()).normalized();
  base_T_hand.linear().col(1) = base_T_hand.linear().col(2).cross(base_T_hand.linear().col(0));
  base_T_hand.translation() = eye + 0.6 * d;
  msg::PoseStamped p;
  msgs::to_msg(base_T_hand, p.pose());
  hand_in.write(p);
  cam.tick(Time{0});
  msg::Image left, right, keyed;
  msg::CameraInfo info;
  image.take_latest(left), image_right.take_latest(right), info_out.take_latest(info);
  Harness keyer("chroma_keyer", "{}", 25);
  auto key_in = keyer.feed<msg::Image>("image");
  auto key_out = keyer.watch<msg::Image>("hand");
  keyer.activate();
  key_in.write(left);
  keyer.tick(Time{0});
  key_out.take_latest(keyed);

  // (no camera pose here: the hand in the camera's frame)
  Harness stereo("stereo_depth", params.substr(0, params.size() - 1) + ", hand_frame: eye}", 25);
  auto left_in = stereo.feed<msg::Image>("left");
  auto right_in = stereo.feed<msg::Image>("right");
  auto info_in = stereo.feed<msg::CameraInfo>("camera_info");
  auto keyed_in = stereo.feed<msg::Image>("keyed");
  auto depth = stereo.watch<msg::Image>("depth", 2);
  auto hand = stereo.watch<msg::HandPosition>("hand_position", 2);
  stereo.activate();
  info_in.write(info);
  msg::Image depth_out;
  msg::HandPosition hand_out;
  std::int64_t t = 0;
  for (auto _ : state) {
    t += 40'000'000;
    left.header().stamp_ns(t), right.header().stamp_ns(t), keyed.header().stamp_ns(t);
    left_in.write(left), right_in.write(right), keyed_in.write(keyed);
    stereo.tick(Time{t});
    if (!depth.take_latest(depth_out) || !hand.take_latest(hand_out))
      state.SkipWithError("no depth or no hand position");
  }
}
BENCHMARK_CAPTURE(BM_StereoDepth_640x480, sgbm_full_size,
                  std::string("{baseline: 0.06, algorithm: sgbm, downscale: 1}"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(wysiwyf::bench::min_time(2.0));
BENCHMARK_CAPTURE(BM_StereoDepth_640x480, sgbm_half_size_default, std::string("{baseline: 0.06}"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(wysiwyf::bench::min_time(2.0));
BENCHMARK_CAPTURE(BM_StereoDepth_640x480, sgbm_3way_half_size, std::string("{baseline: 0.06, algorithm: sgbm_3way}"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(wysiwyf::bench::min_time(2.0));
BENCHMARK_CAPTURE(BM_StereoDepth_640x480, bm_full_size,
                  std::string("{baseline: 0.06, algorithm: bm, block_size: 9, downscale: 1}"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(wysiwyf::bench::min_time(2.0));

// marker_tracker through its ports on 50 camera_sim frames (its default camera position, looking
// at the plate; the arm at the demo's start, swaying), cycled: joint state + image in, poses,
// covariances and observation out. Tracking: search windows only. LoseAndReacquire: a frame
// without lamps (lost at once, lost_after 1) then a whole-frame search and a fresh start (a PnP
// fix, or from the last estimate where the arm hides lamps under the table), per pair.
struct TrackerFrames {
  std::vector<msg::JointState> joints;
  std::vector<msg::Image> images;
  msg::Image dark;  // the first view with every lamp off
};
const TrackerFrames& tracker_frames() {
  static const TrackerFrames frames = [] {
    TrackerFrames f;
    const double q0[6] = {0.255486, -0.429048, -2.231546, 0.286487, 1.106586, 3.010371};
    msg::JointState js;
    js.position().resize(6);
    for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = q0[i];
    // Where the plate is (camera_sim's ground truth), so that the camera looks at it.
    Eigen::Vector3d plate;
    {
      Harness probe("camera_sim", "{}", 25);
      auto joints = probe.feed<msg::JointState>("joint_state");
      auto eye_T_base = probe.watch<msg::PoseStamped>("true_eye_T_base");
      auto eye_T_dev = probe.watch<msg::PoseStamped>("true_eye_T_dev");
      probe.activate();
      joints.write(js);
      probe.tick(Time{0});
      msg::PoseStamped b, d;
      eye_T_base.take_latest(b), eye_T_dev.take_latest(d);
      plate = (msgs::to_isometry(b.pose()).inverse() * msgs::to_isometry(d.pose())).translation();
    }
    const std::string look_at = "look_at: [" + std::to_string(plate.x()) + ", " + std::to_string(plate.y()) + ", " +
                                std::to_string(plate.z()) + "]";
    Harness cam("camera_sim", "{" + look_at + "}", 25);
    auto joints = cam.feed<msg::JointState>("joint_state");
    auto image = cam.watch<msg::Image>("image");
    cam.activate();
    for (int k = 0; k < 50; ++k) {
      js.header().stamp_ns(k * 40'000'000LL);
      for (int i = 0; i < 6; ++i) js.position()[i] = q0[i] + 0.05 * std::sin(2 * M_PI * 0.5 * k * 0.04 + i);
      joints.write(js);
      cam.tick(Time{k * 40'000'000LL});
      f.joints.push_back(js);
      f.images.emplace_back();
      image.take_latest(f.images.back());
    }
    Harness off("camera_sim",
                "{" + look_at + ", hidden_markers: [0, 1.0e6, 0,  0, 1.0e6, 1,  0, 1.0e6, 2,  0, 1.0e6, 3]}", 25);
    auto off_joints = off.feed<msg::JointState>("joint_state");
    auto off_image = off.watch<msg::Image>("image");
    off.activate();
    off_joints.write(f.joints.front());
    off.tick(Time{0});
    off_image.take_latest(f.dark);
    return f;
  }();
  return frames;
}

void run_marker_tracker(benchmark::State& state, bool lose_every_other) {
  const auto& frames = tracker_frames();
  Harness tracker("marker_tracker",
                  lose_every_other ? "{intrinsics: [600, 600, 319.5, 239.5], lost_after: 1}"
                                   : "{intrinsics: [600, 600, 319.5, 239.5]}",
                  25);
  auto joints = tracker.feed<msg::JointState>("joint_state");
  auto image = tracker.feed<msg::Image>("image");
  auto markers = tracker.watch<msg::MarkerObservation>("markers", 2);
  auto pose = tracker.watch<msg::PoseStamped>("eye_T_base", 2);
  tracker.activate();
  msg::MarkerObservation obs;
  msg::PoseStamped out;
  std::int64_t t = 0;
  std::size_t i = 0;
  int not_tracking = 0, fixes = 0;
  auto feed = [&](msg::JointState js, msg::Image& img) {
    t += 40'000'000;
    js.header().stamp_ns(t), img.header().stamp_ns(t);
    joints.write(js);
    image.write(img);
    tracker.tick(Time{t});
    markers.take_latest(obs);
    pose.take_latest(out);
  };
  std::vector<msg::Image> images = frames.images;  // restamped as time goes on; the port copies them
  msg::Image dark = frames.dark;
  for (auto _ : state) {
    const std::size_t k = i++ % images.size();
    if (lose_every_other) feed(frames.joints[k], dark);
    feed(frames.joints[k], images[k]);
    not_tracking += obs.status() != msg::TRACKING_OK;
    fixes += obs.acquired();
  }
  // Per iteration: images after which the tracker was not tracking, and fresh starts of its filter.
  state.counters["not_tracking"] = benchmark::Counter(not_tracking, benchmark::Counter::kAvgIterations);
  state.counters["fixes"] = benchmark::Counter(fixes, benchmark::Counter::kAvgIterations);
}
void BM_MarkerTracker_Tracking_640x480(benchmark::State& state) { run_marker_tracker(state, false); }
void BM_MarkerTracker_LoseAndReacquire_640x480(benchmark::State& state) { run_marker_tracker(state, true); }
BENCHMARK(BM_MarkerTracker_Tracking_640x480)->Unit(benchmark::kMillisecond)->MinTime(wysiwyf::bench::min_time(1.0));
BENCHMARK(BM_MarkerTracker_LoseAndReacquire_640x480)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(wysiwyf::bench::min_time(1.0));

}  // namespace wysiwyf::vision

BENCHMARK_MAIN();
