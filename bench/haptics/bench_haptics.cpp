// Haptics benchmarks: one haptic step of the admittance simulation (the paper's cube resting on
// its table, 4 contacts, a user push), the contact LCP against contact count, a 1 kHz real-time
// loop, and the peer: MuJoCo stepping the same 1 kg, 20 cm cube on a frictionless plane at 1 ms
// with the same push, in the same run.
#include <benchmark/benchmark.h>
#include <sys/prctl.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <memory>
#include <string>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include "rigid_body/world.hpp"
#include "mujoco_peer.hpp"
#include "wysiwyf/tick_deadline.hpp"
#include "../common/smoke.hpp"

namespace wysiwyf::haptics {

using Clock = std::chrono::steady_clock;

World cube_on_table(double rtol = kHapticRtol, double friction = 0.0) {
  BodyModel cube;
  cube.name = "cube";
  cube.half_extents = Vec3::Constant(0.1);
  cube.mass = 1.0;
  cube.inertia_body = BodyModel::box_inertia(1.0, cube.half_extents);
  BodyModel table;
  table.name = "table";
  table.dynamic = false;
  table.half_extents = Vec3(50, 50, 0.05);  // large: the push never reaches its edge
  table.friction = friction;
  BodyState c, t;
  c.x = Vec3(0, 0, 0.1);
  t.x = Vec3(0, 0, -0.05);
  WorldParams p;
  p.rtol = rtol;  // admittance_sim's default: kHapticRtol (1e-7)
  p.atol = rtol * 1e-2;
  return World({cube, table}, {c, t}, p);
}

void percentiles(benchmark::State& state, std::vector<double>& us) {
  std::sort(us.begin(), us.end());
  state.counters["p50_us"] = us[us.size() / 2];
  state.counters["p99_us"] = us[us.size() * 99 / 100];
}

// A new sensor sample every step (noise on a push swaying 2 cos t N, which keeps the cube on the
// table for the 20 s of 20000 steps): the integrator restarts every step.
void noisy_push_steps(benchmark::State& state, World w) {
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0, 0.05);
  std::vector<double> us;
  double rhs = 0, steps = 0, rounds = 0, t = 0;
  for (auto _ : state) {
    w.set_external_wrench(0, Vec3(2 * std::cos(t) + noise(rng), noise(rng), noise(rng)), Vec3::Zero());
    t += 1e-3;
    const auto t0 = Clock::now();
    const StepReport r = w.step(1e-3);
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    state.SetIterationTime(dt);
    us.push_back(dt * 1e6);
    rhs += r.rhs_evaluations, steps += r.integrator_steps, rounds += r.friction_rounds;
  }
  state.counters["contacts"] = static_cast<double>(w.resting_contacts().size());
  state.counters["rhs"] = rhs / static_cast<double>(us.size());  // right-hand sides a haptic step
  state.counters["integrator_steps"] = steps / static_cast<double>(us.size());
  if (rounds > 0) state.counters["friction_rounds"] = rounds / static_cast<double>(us.size());
  percentiles(state, us);
}
void BM_HapticStep_RestingCube_NoisyPush(benchmark::State& state) {
  noisy_push_steps(state, cube_on_table(std::pow(10.0, -static_cast<double>(state.range(0)))));
}
// Argument: -log10 of the integrator's relative tolerance (7: admittance_sim's default).
BENCHMARK(BM_HapticStep_RestingCube_NoisyPush)
    ->Arg(7)
    ->Arg(8)
    ->Arg(6)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);

// The noisy push on a table with Coulomb friction mu = 0.4 (the push stays below mu m g: the cube
// sticks): the friction solve at each step's start comes on top.
void BM_HapticStep_RestingCube_NoisyPush_Friction(benchmark::State& state) {
  noisy_push_steps(state, cube_on_table(kHapticRtol, 0.4));
}
BENCHMARK(BM_HapticStep_RestingCube_NoisyPush_Friction)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);

// The same push held constant: no restart (the integrator keeps its history across steps).
void BM_HapticStep_RestingCube_ConstantPush(benchmark::State& state) {
  World w = cube_on_table();
  w.set_external_wrench(0, Vec3(2, 0, 0), Vec3::Zero());
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  std::vector<double> us;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    w.step(1e-3);
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    state.SetIterationTime(dt);
    us.push_back(dt * 1e6);
  }
  state.counters["sink_mm"] = std::max(0.0, (0.1 - w.state(0).x.z()) * 1e3);
  percentiles(state, us);
}
BENCHMARK(BM_HapticStep_RestingCube_ConstantPush)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(5000))
    ->Unit(benchmark::kMicrosecond);

// The LCP alone: n contacts spread over the bottom face of a resting cube.
void BM_Lcp(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::MatrixXd J(n, 6);
  for (int i = 0; i < n; ++i) {
    const Vec3 r(u(rng), u(rng), -0.1), nrm = Vec3::UnitZ();
    J.row(i) << nrm.transpose(), r.cross(nrm).transpose();
  }
  Eigen::MatrixXd Minv = Eigen::MatrixXd::Identity(6, 6);
  Minv.bottomRightCorner<3, 3>() *= 1.0 / (0.04 / 6);
  const Eigen::MatrixXd A = J * Minv * J.transpose();
  Eigen::VectorXd F(6);
  F << 2, 0, -9.81, 0.1, -0.05, 0;
  const Eigen::VectorXd b = J * Minv * F;
  LcpSolver solver;
  for (auto _ : state) benchmark::DoNotOptimize(solver.solve(A, b));
}
BENCHMARK(BM_Lcp)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMicrosecond);

// A 1 kHz loop on the wall clock for 10 s: absolute deadlines, one haptic step per tick, each
// with a new noisy sample of a swaying push (as from the wrist sensor: a restart every tick).
// It waits as the kernel's real-time executor does: it sleeps until `spin` before each deadline
// and busy-waits the rest (argument: spin in us; 0 is the executor's default, 100 what the
// haptic pipelines ask for with `spin: 100us`), and like it skips the deadlines a tick has
// already missed by a whole period, counting them as overruns (a stall of the virtual machine
// is then one late tick, not a run of them).
void BM_RealTimeLoop_1kHz_10s(benchmark::State& state) {
  prctl(PR_SET_TIMERSLACK, 1UL);  // Linux lets a normal thread wake up to 50 us late by default
  const auto spin = std::chrono::microseconds(state.range(0));
  const std::atomic<bool> never{false};
  for (auto _ : state) {
    World w = cube_on_table();
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0, 0.05);
    std::vector<double> late_us, step_us;
    const auto period = std::chrono::milliseconds(1);
    const auto start = Clock::now();
    auto next = start + period;
    int ticks = 0;
    std::uint64_t overruns = 0;
    while (next - start <= wysiwyf::bench::duration(std::chrono::seconds(10))) {
      std::this_thread::sleep_until(next - spin);
      spin_until(next, never);
      late_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - next).count());
      w.set_external_wrench(0, Vec3(2 * std::cos(ticks * 1e-3) + noise(rng), noise(rng), noise(rng)), Vec3::Zero());
      const auto t0 = Clock::now();
      w.step(1e-3);
      step_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      ++ticks;
      overruns += advance_deadline(next, period);
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    state.counters["rate_hz"] = ticks / seconds;
    state.counters["overruns"] = static_cast<double>(overruns);
    std::sort(late_us.begin(), late_us.end());
    state.counters["jitter_p50_us"] = late_us[late_us.size() / 2];
    state.counters["jitter_p99_us"] = late_us[late_us.size() * 99 / 100];
    state.counters["jitter_max_us"] = late_us.back();
    std::sort(step_us.begin(), step_us.end());
    state.counters["step_p99_us"] = step_us[step_us.size() * 99 / 100];
  }
}
BENCHMARK(BM_RealTimeLoop_1kHz_10s)
    ->Arg(0)
    ->Arg(100)
    ->Iterations(wysiwyf::bench::iterations(1))
    ->Unit(benchmark::kSecond);

#ifdef WYSIWYF_HAVE_MUJOCO
// The peer: MuJoCo, the same 1 kg, 20 cm cube on a frictionless plane, 1 ms steps.
class MujocoCube : public MujocoScene {
 public:
  MujocoCube()
      : MujocoScene(R"(
<mujoco>
  <option timestep="0.001"/>
  <worldbody>
    <geom type="plane" size="50 50 0.1" condim="1"/>
    <body pos="0 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1" mass="1" condim="1"/>
    </body>
  </worldbody>
</mujoco>)") {}
  void push(const Vec3& f) { MujocoScene::push(0, f); }
  double sink() const { return MujocoScene::sink(0, 0.1); }
};

// MuJoCo alone, the push held at 2 N.
void BM_MuJoCo_Step_RestingCube_Push(benchmark::State& state) {
  MujocoCube mj;
  if (!mj.error().empty()) return state.SkipWithError(mj.error().c_str());
  mj.push(Vec3(2, 0, 0));
  std::vector<double> us;
  double sink = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    mj.step();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    state.SetIterationTime(dt);
    us.push_back(dt * 1e6);
    sink = std::max(sink, mj.sink());
  }
  state.counters["sink_mm"] = sink * 1e3;
  percentiles(state, us);
}
BENCHMARK(BM_MuJoCo_Step_RestingCube_Push)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(5000))
    ->Unit(benchmark::kMicrosecond);

// The comparison the goal is about: our haptic step (admittance_sim's tolerance) and MuJoCo's,
// alternately, on the same noisy sampled push, so both see the same load of this shared machine.
// The push sways (2 cos t N, plus the noise) so that 20 s keep the cube on the table.
// Manual time is ours; ratio_p50 = our p50 / MuJoCo's p50.
void BM_Peer_Interleaved_NoisyPush(benchmark::State& state) {
  MujocoCube mj;
  if (!mj.error().empty()) return state.SkipWithError(mj.error().c_str());
  World w = cube_on_table();
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0, 0.05);
  std::vector<double> ours, theirs;
  double sink = 0;
  double t = 0;
  for (auto _ : state) {
    const Vec3 f(2 * std::cos(t) + noise(rng), noise(rng), noise(rng));
    t += 1e-3;
    w.set_external_wrench(0, f, Vec3::Zero());
    mj.push(f);
    const auto t0 = Clock::now();
    w.step(1e-3);
    const auto t1 = Clock::now();
    mj.step();
    const auto t2 = Clock::now();
    const double dt = std::chrono::duration<double>(t1 - t0).count();
    state.SetIterationTime(dt);
    ours.push_back(dt * 1e6);
    theirs.push_back(std::chrono::duration<double>(t2 - t1).count() * 1e6);
    sink = std::max(sink, mj.sink());
  }
  std::sort(ours.begin(), ours.end());
  std::sort(theirs.begin(), theirs.end());
  state.counters["ours_p50_us"] = ours[ours.size() / 2];
  state.counters["ours_p99_us"] = ours[ours.size() * 99 / 100];
  state.counters["mujoco_p50_us"] = theirs[theirs.size() / 2];
  state.counters["ratio_p50"] = ours[ours.size() / 2] / theirs[theirs.size() / 2];
  state.counters["mujoco_sink_mm"] = sink * 1e3;
  state.counters["our_sink_mm"] = std::max(0.0, (0.1 - w.state(0).x.z()) * 1e3);
}
BENCHMARK(BM_Peer_Interleaved_NoisyPush)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);
#endif

}  // namespace wysiwyf::haptics

BENCHMARK_MAIN();
