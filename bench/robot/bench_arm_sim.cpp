// arm_sim's real-time factor on each shipped arm (the PUMA 560 with its drive train, the UR5e
// and the FR3 with ideal drives, parked as their robots/<arm>-sim.yaml): 1 kHz ticks run through
// the Harness (no DDS, no executor), the arm following a 50 Hz Cartesian setpoint stream (a 3 cm
// circle at 0.5 Hz around its parked pose), with the fingertip parked, or pressing on the plate
// (contact, Jacobian, sensor each substep). The time per iteration is the tick's cost.
// Counters: real_time_factor = simulated seconds per wall second (ticks per second / 1000; goal
// >= 20), allocs_per_tick = operator new calls per tick in steady state.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "../common/allocation_counter.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "../common/smoke.hpp"

namespace {

using namespace wysiwyf;
constexpr std::int64_t kMs = 1'000'000;
constexpr double kPi = 3.14159265358979323846;

void run(benchmark::State& state, bool touch, const char* params) {
  Harness h("arm_sim", params, 1000);
  auto setpoints = h.feed<msg::CartesianSetpoint>("setpoint");
  auto hand = h.feed<msg::PoseStamped>("hand_target");
  auto pose_in = h.watch<msg::PoseStamped>("device_pose", 2);
  auto status_in = h.watch<msg::RobotStatus>("status", 16);
  h.activate();
  std::int64_t t = 0;
  h.tick(Time{t});
  msg::PoseStamped first;
  if (!pose_in.take_latest(first)) {
    state.SkipWithError("no device_pose");
    return;
  }
  const Eigen::Isometry3d ready = msgs::to_isometry(first.pose());
  // The fingertip, if it touches: from its park (default (1.1, 0, 0.2) m) in 1 s to 2 cm in front
  // of the plate, then in 0.5 s to 3 cm behind its face (a firm push of about 19 N).
  msg::PoseStamped target;
  target.header().frame_id("base");
  target.pose().orientation().w(1.0);
  const Eigen::Vector3d park(1.1, 0.0, 0.2), front = ready * Eigen::Vector3d(0.05, 0.04, 0.02),
                                             behind = ready * Eigen::Vector3d(0.05, 0.04, -0.03);
  auto move_hand = [&](int ms) {
    if (!touch || ms > 1500) return;
    const Eigen::Vector3d p =
        ms < 1000 ? park + (front - park) * (ms / 1000.0) : front + (behind - front) * ((ms - 1000) / 500.0);
    target.pose().position().x(p.x());
    target.pose().position().y(p.y());
    target.pose().position().z(p.z());
    hand.write(target);
  };
  msg::CartesianSetpoint sp;
  sp.header().frame_id("base");
  sp.child_frame_id("dev");
  sp.source("bench");
  const Eigen::Quaterniond q(ready.linear());
  sp.pose().orientation().x(q.x());
  sp.pose().orientation().y(q.y());
  sp.pose().orientation().z(q.z());
  sp.pose().orientation().w(q.w());
  const double w = 2 * kPi * 0.5, r = 0.03;
  auto tick = [&] {
    t += kMs;
    if ((t / kMs) % 20 == 0) {
      const double s = static_cast<double>(t) * 1e-9;
      const Eigen::Vector3d p = ready.translation() + r * Eigen::Vector3d(0, std::sin(w * s), 1 - std::cos(w * s));
      sp.header().stamp_ns(t);
      sp.pose().position().x(p.x());
      sp.pose().position().y(p.y());
      sp.pose().position().z(p.z());
      sp.twist().linear().y(r * w * std::cos(w * s));
      sp.twist().linear().z(r * w * std::sin(w * s));
      setpoints.write(sp);
    }
    h.tick(Time{t});
  };
  for (int i = 0; i < 2500; ++i) {  // warm up: the hand reaches the plate, buffers settle
    move_hand(i);
    tick();
  }
  const std::uint64_t allocations = bench::allocation_count();
  for (auto _ : state) tick();
  const double ticks = static_cast<double>(state.iterations());
  state.counters["real_time_factor"] = benchmark::Counter(ticks / 1000.0, benchmark::Counter::kIsRate);
  state.counters["allocs_per_tick"] = static_cast<double>(bench::allocation_count() - allocations) / ticks;
  msg::RobotStatus status;
  while (status_in.take(status)) {
  }
  if (status.state() == msg::ARM_FAULT) state.SkipWithError(status.reason().c_str());
}

void BM_ArmSimFollowing(benchmark::State& state, const char* params) { run(state, false, params); }
void BM_ArmSimHandOnPlate(benchmark::State& state, const char* params) { run(state, true, params); }

constexpr const char* kPuma = "{}";  // arm_sim's defaults: the PUMA 560, its drive file, its ready pose
constexpr const char* kUr5e =
    "{urdf: robots/ur5e.urdf, drive: '', acceleration_limits: [8, 8, 10, 30, 30, 30],"
    " initial_q: [2.802180, -1.581828, 1.807510, -0.225596, 1.231347, 1.570657]}";
constexpr const char* kFr3 =
    "{urdf: robots/fr3.urdf, drive: '', acceleration_limits: [10, 10, 10, 10, 10, 10, 10],"
    " initial_q: [0.284092, 0.238745, -0.305931, -2.463769, -0.015183, 4.263556, -1.493028]}";

#define WYSIWYF_ARM_SIM_BENCHMARKS(arm, params)        \
  BENCHMARK_CAPTURE(BM_ArmSimFollowing, arm, params)   \
      ->UseRealTime()                                  \
      ->MinTime(wysiwyf::bench::min_time(2.0))         \
      ->Unit(benchmark::kMicrosecond);                 \
  BENCHMARK_CAPTURE(BM_ArmSimHandOnPlate, arm, params) \
      ->UseRealTime()                                  \
      ->MinTime(wysiwyf::bench::min_time(2.0))         \
      ->Unit(benchmark::kMicrosecond)

WYSIWYF_ARM_SIM_BENCHMARKS(puma560, kPuma);
WYSIWYF_ARM_SIM_BENCHMARKS(ur5e, kUr5e);
WYSIWYF_ARM_SIM_BENCHMARKS(fr3, kFr3);

}  // namespace

BENCHMARK_MAIN();
