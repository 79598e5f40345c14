// Rendering benchmarks: one renderer frame at 640x480 (draw the scene, read back colour and
// depth, publish both), headless on whatever EGL finds (llvmpipe on a machine without a GPU).
#include <chrono>
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "../common/smoke.hpp"

namespace wysiwyf::render {

void BM_Renderer_640x480(benchmark::State& state) {
  const std::string params = "{samples: " + std::to_string(state.range(0)) + "}";
  Harness h("renderer", params, 60);
  auto info_in = h.feed<msg::CameraInfo>("camera_info");
  auto pose_in = h.feed<msg::PoseStamped>("eye_T_base");
  auto color = h.watch<msg::Image>("color", 2);
  h.activate();
  msg::CameraInfo info;
  info.width(640), info.height(480);
  info.k() = {600, 0, 319.5, 0, 600, 239.5, 0, 0, 1};
  info_in.write(info);
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  base_T_eye.linear() << 1, 0, 0, 0, 0.6, 0.8, 0, -0.8, 0.6;  // looking down at the table
  base_T_eye.translation() = Eigen::Vector3d(0.6, -0.7, 0.6);
  msg::PoseStamped p;
  msgs::to_msg(base_T_eye.inverse(), p.pose());
  pose_in.write(p);
  std::int64_t t = 0;
  msg::Image img;
  for (auto _ : state) {
    h.tick(Time{t += 16'666'667});
    color.take_latest(img);
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Renderer_640x480)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond)->MinTime(wysiwyf::bench::min_time(2.0));

// camera_sim: colour pass, mask pass, depth read-back, spill, blur, noise, ground truth.
void BM_CameraSim_640x480(benchmark::State& state) {
  Harness h("camera_sim", "{}", 30);
  auto joints = h.feed<msg::JointState>("joint_state");
  auto image = h.watch<msg::Image>("image", 2);
  h.activate();
  msg::JointState js;
  const double q[6] = {0.37, 0.47, -3.17, 0.96, 1.62, 1.19};  // the plate in view
  js.position().resize(6);
  for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = q[i];
  joints.write(js);
  std::int64_t t = 0;
  msg::Image img;
  for (auto _ : state) {
    h.tick(Time{t += 33'333'333});
    image.take_latest(img);
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CameraSim_640x480)->Unit(benchmark::kMillisecond)->MinTime(wysiwyf::bench::min_time(2.0));

// compositor: the keyed hand (premultiplied RGBA) over a 640x480 scene, alpha only and z-keyed.
void BM_Compositor_640x480(benchmark::State& state) {
  const bool zkey = state.range(0) != 0;
  Harness h("compositor", "{}", 60);
  auto scene = h.feed<msg::Image>("scene");
  auto scene_depth = h.feed<msg::Image>("scene_depth");
  auto hand = h.feed<msg::Image>("hand");
  auto real_depth = h.feed<msg::Image>("real_depth");
  auto out = h.watch<msg::Image>("composite", 2);
  h.activate();
  auto make = [](const char* enc, int bytes, std::uint8_t fill) {
    msg::Image m;
    m.width(640), m.height(480), m.encoding(enc), m.step(640 * bytes);
    m.data().assign(640 * 480 * bytes, fill);
    return m;
  };
  msg::Image s = make("rgb8", 3, 90), k = make("rgba8", 4, 0), sd = make("32FC1", 4, 0), rd = make("32FC1", 4, 0);
  for (std::size_t i = 0; i < k.data().size(); i += 4)  // a hand over a third of the frame, soft edges
    if ((i / 4) % 640 < 213) k.data()[i] = 150, k.data()[i + 3] = static_cast<std::uint8_t>(128 + (i / 4) % 127);
  std::int64_t t = 0;
  msg::Image img;
  double whole = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    scene.write(s), hand.write(k);
    if (zkey) scene_depth.write(sd), real_depth.write(rd);
    const auto t1 = std::chrono::steady_clock::now();
    h.tick(Time{t += 16'666'667});  // what the pipeline's tick costs: take the inputs, composite, publish
    const auto t2 = std::chrono::steady_clock::now();
    out.take_latest(img);
    state.SetIterationTime(std::chrono::duration<double>(t2 - t1).count());
    whole += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  // With the test's own feeding of the inputs and reading of the output.
  state.counters["with_feeding_ms"] = whole * 1e3 / static_cast<double>(state.iterations());
}
// Time: the component's tick alone (manual time).
BENCHMARK(BM_Compositor_640x480)
    ->Arg(0)
    ->Arg(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(wysiwyf::bench::min_time(1.0));

}  // namespace wysiwyf::render

BENCHMARK_MAIN();
