// Vision benchmarks: the chroma keyer on 640x480 camera_sim frames (hand over blue cloth).
#include <benchmark/benchmark.h>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::vision {

void BM_ChromaKeyer_640x480(benchmark::State& state) {
  Harness cam("camera_sim", "{}", 25);
  auto hand_in = cam.feed<msg::PoseStamped>("hand_pose");
  auto image = cam.watch<msg::Image>("image");
  cam.activate();
  Eigen::Isometry3d base_T_hand = Eigen::Isometry3d::Identity();
  base_T_hand.linear() = Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  base_T_hand.translation() = Eigen::Vector3d(0.7, -0.05, 0.35);
  msg::PoseStamped p;
  msgs::to_msg(base_T_hand, p.pose());
  hand_in.write(p);
  cam.tick(Time{0});
  msg::Image frame;
  image.take_latest(frame);
  Harness keyer("chroma_keyer", "{}", 25);
  auto in = keyer.feed<msg::Image>("image");
  auto hand = keyer.watch<msg::Image>("hand", 2);
  keyer.activate();
  msg::Image out;
  std::int64_t t = 0;
  for (auto _ : state) {
    in.write(frame);
    keyer.tick(Time{t += 40'000'000});
    hand.take_latest(out);
  }
  state.counters["Mpixel_per_s"] =
      benchmark::Counter(640.0 * 480.0 * static_cast<double>(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ChromaKeyer_640x480)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace wysiwyf::vision

BENCHMARK_MAIN();
