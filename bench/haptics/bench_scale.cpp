// Haptics at scale (issue 16): one haptic step against the number of bodies, next to MuJoCo
// stepping the same scene in the same run, alternately (as BM_Peer_Interleaved_NoisyPush does
// for the single cube), and the same for a stack.
//  - Grid/N: N 10 cm, 1 kg cubes resting on a table 15 cm apart; the device pushes the first
//    with a new noisy sample every step (0.5 cos 2 pi t N plus noise: it sways 2.5 cm and never
//    reaches the next cube). Every body is integrated together; each rests on its own 4
//    contacts (an island of its own).
//  - Stack/N: N such cubes stacked, the device pushing the top one sideways (0.5 cos 2 pi t N
//    plus noise, below what friction holds: mu 0.5). One island of 4 + 8 (N - 1) contacts.
//  - GridSleeping/N: the grid as admittance_sim runs it, sleeping (WorldParams::sleep_after): the
//    cubes the device does not push fall asleep and leave the integration. The rows above keep
//    every body integrated every step, as MuJoCo (2.2: no sleeping) does.
// Frictionless for the grid (the single-cube peer row's condim 1), friction for the stack (MuJoCo
// condim 3, the same mu). Reported: our and MuJoCo's p50 / p99, their ratio, and each one's
// deepest sink. The growth exponent is the slope of log p50 against log N (README).
// Instructions per step: run under callgrind by bench/haptics/instructions.py (scripts/bench
// haptics), with WYSIWYF_BENCH_COUNT=ours or mujoco, only that one's steps are collected and each
// benchmark's count is dumped under its name (this VM has no hardware counters).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define WYSIWYF_CALLGRIND 1
#endif

#include "rigid_body/broad_phase.hpp"
#include "rigid_body/world.hpp"
#include "mujoco_peer.hpp"
#include "../common/smoke.hpp"

namespace wysiwyf::haptics {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kHalf = 0.05, kMass = 1.0;

// Which of the two steps callgrind counts (WYSIWYF_BENCH_COUNT); natively the requests are no-ops.
enum class Counted { kNone, kOurs, kMujoco };
Counted counted() {
  static const Counted c = [] {
    const std::string v = std::getenv("WYSIWYF_BENCH_COUNT") ? std::getenv("WYSIWYF_BENCH_COUNT") : "";
    return v == "ours" ? Counted::kOurs : v == "mujoco" ? Counted::kMujoco : Counted::kNone;
  }();
  return c;
}
void toggle_count([[maybe_unused]] Counted who) {
#ifdef WYSIWYF_CALLGRIND
  if (counted() == who) CALLGRIND_TOGGLE_COLLECT;
#endif
}
// The instructions counted so far go out under this benchmark's name and step count.
void dump_count([[maybe_unused]] const std::string& name, [[maybe_unused]] const benchmark::State& state) {
#ifdef WYSIWYF_CALLGRIND
  if (counted() == Counted::kNone) return;
  const std::string label = name + " steps=" + std::to_string(state.iterations());  // (alive through the request)
  CALLGRIND_DUMP_STATS_AT(label.c_str());
#endif
}

struct Layout {
  std::vector<Vec3> centres;  // of the cubes, resting
  double mu = 0;
};

Layout grid(int n) {
  Layout l;
  const int columns = static_cast<int>(std::ceil(std::sqrt(n)));
  for (int i = 0; i < n; ++i) l.centres.emplace_back(0.15 * (i % columns), 0.15 * (i / columns), kHalf);
  return l;
}

Layout stack(int n) {
  Layout l;
  for (int i = 0; i < n; ++i) l.centres.emplace_back(0, 0, kHalf + 2 * kHalf * i);
  l.mu = 0.5;
  return l;
}

World our_world(const Layout& l, bool sleeping) {
  std::vector<BodyModel> models;
  std::vector<BodyState> states;
  for (std::size_t i = 0; i < l.centres.size(); ++i) {
    BodyModel cube;
    cube.name = "cube" + std::to_string(i);
    cube.half_extents = Vec3::Constant(kHalf);
    cube.mass = kMass;
    cube.inertia_body = BodyModel::box_inertia(kMass, cube.half_extents);
    cube.friction = l.mu;
    models.push_back(cube);
    BodyState s;
    s.x = l.centres[i];
    states.push_back(s);
  }
  BodyModel table;
  table.name = "table";
  table.dynamic = false;
  table.half_extents = Vec3(50, 50, 0.05);
  table.friction = l.mu;
  models.push_back(table);
  BodyState t;
  t.x = Vec3(0, 0, -0.05);
  states.push_back(t);
  WorldParams p;
  p.rtol = kHapticRtol;  // admittance_sim's
  p.atol = kHapticRtol * 1e-2;
  if (!sleeping) p.sleep_after = 0;
  return World(models, states, p);
}

std::string mujoco_xml(const Layout& l) {
  const std::string contact = l.mu > 0 ? "condim=\"3\" friction=\"" + std::to_string(l.mu) + " 0 0\"" : "condim=\"1\"";
  // (MuJoCo 2.2 sizes its contact buffers from the model: 100 contacts unless told, and a full
  // buffer drops contacts, letting boxes fall through the plane)
  const std::string room = std::to_string(16 * l.centres.size() + 100);
  std::string xml = "<mujoco><option timestep=\"0.001\"/><size nconmax=\"" + room + "\" njmax=\"" + room +
                    "0\"/><worldbody><geom type=\"plane\" size=\"50 50 0.1\" " + contact + "/>";
  for (const Vec3& c : l.centres)
    xml += "<body pos=\"" + std::to_string(c.x()) + " " + std::to_string(c.y()) + " " + std::to_string(c.z()) +
           "\"><freejoint/><geom type=\"box\" size=\"0.05 0.05 0.05\" mass=\"1\" " + contact + "/></body>";
  return xml + "</worldbody></mujoco>";
}

double deepest_sink(const World& w, const Layout& l) {
  double sink = 0;
  for (std::size_t i = 0; i < l.centres.size(); ++i)
    sink = std::max(sink, l.centres[i].z() - w.state(static_cast<int>(i)).x.z());
  return sink;
}

void interleaved(benchmark::State& state, const std::string& name, const Layout& l, int pushed, double amplitude,
                 const Vec3& along, bool sleeping = false) {
  World w = our_world(l, sleeping);
  for (int i = 0; i < 100; ++i) w.step(1e-3);
#ifdef WYSIWYF_HAVE_MUJOCO
  MujocoScene mj(mujoco_xml(l));
  if (!mj.error().empty()) return state.SkipWithError(mj.error().c_str());
#endif
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0, 0.05);
  std::vector<double> ours, theirs;
  double t = 0, our_sink = 0, their_sink = 0;
  for (auto _ : state) {
    const Vec3 f = amplitude * std::cos(2 * M_PI * t) * along + Vec3(noise(rng), noise(rng), noise(rng));
    t += 1e-3;
    w.set_external_wrench(pushed, f, Vec3::Zero());
    toggle_count(Counted::kOurs);
    const auto t0 = Clock::now();
    w.step(1e-3);
    const auto t1 = Clock::now();
    toggle_count(Counted::kOurs);
    const double dt = std::chrono::duration<double>(t1 - t0).count();
    state.SetIterationTime(dt);
    ours.push_back(dt * 1e6);
    our_sink = std::max(our_sink, deepest_sink(w, l));
#ifdef WYSIWYF_HAVE_MUJOCO
    mj.push(pushed, f);
    toggle_count(Counted::kMujoco);
    const auto t2 = Clock::now();
    mj.step();
    const auto t3 = Clock::now();
    toggle_count(Counted::kMujoco);
    theirs.push_back(std::chrono::duration<double>(t3 - t2).count() * 1e6);
    for (std::size_t i = 0; i < l.centres.size(); ++i)
      their_sink = std::max(their_sink, mj.sink(static_cast<int>(i), l.centres[i].z()));
#endif
  }
  dump_count(name, state);
  const auto p = [](std::vector<double>& v, int percent) {
    std::sort(v.begin(), v.end());
    return v[v.size() * static_cast<std::size_t>(percent) / 100];
  };
  state.counters["bodies"] = static_cast<double>(l.centres.size());
  state.counters["contacts"] = static_cast<double>(w.resting_contacts().size());
  state.counters["ours_p50_us"] = p(ours, 50);
  state.counters["ours_p99_us"] = p(ours, 99);
  state.counters["our_sink_mm"] = our_sink * 1e3;
#ifdef WYSIWYF_HAVE_MUJOCO
  if (mj.overflowed()) return state.SkipWithError("MuJoCo's contact buffer overflowed: not a comparable step");
#endif
  if (!theirs.empty()) {
    state.counters["mujoco_p50_us"] = p(theirs, 50);
    state.counters["mujoco_p99_us"] = p(theirs, 99);
    state.counters["ratio_p50"] = p(ours, 50) / p(theirs, 50);
    state.counters["mujoco_sink_mm"] = their_sink * 1e3;
  }
}

void BM_Scale_Grid(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  interleaved(state, "Grid/" + std::to_string(n), grid(n), 0, 0.5, Vec3::UnitX());
}
BENCHMARK(BM_Scale_Grid)
    ->RangeMultiplier(2)
    ->Range(1, 32)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(5000))
    ->Unit(benchmark::kMicrosecond);

void BM_Scale_GridSleeping(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  interleaved(state, "GridSleeping/" + std::to_string(n), grid(n), 0, 0.5, Vec3::UnitX(), true);
}
BENCHMARK(BM_Scale_GridSleeping)
    ->RangeMultiplier(2)
    ->Range(1, 32)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(5000))
    ->Unit(benchmark::kMicrosecond);

void BM_Scale_Stack(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  interleaved(state, "Stack/" + std::to_string(n), stack(n), n - 1, 0.5, Vec3::UnitX());
}
BENCHMARK(BM_Scale_Stack)
    ->DenseRange(1, 5)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(3000))
    ->Unit(benchmark::kMicrosecond);

// The broad phase on the grid's poses (N cubes and the table): the sweep against testing every
// pair, arg 1 = sweep, 0 = every pair.
void BM_BroadPhase_Grid(benchmark::State& state) {
  const Layout l = grid(static_cast<int>(state.range(0)));
  std::vector<BodyModel> models(l.centres.size() + 1);
  std::vector<Pose> poses(models.size());
  for (std::size_t i = 0; i < l.centres.size(); ++i) {
    models[i].half_extents = Vec3::Constant(kHalf);
    poses[i].x = l.centres[i];
    poses[i].R.setIdentity();
  }
  models.back().dynamic = false;
  models.back().half_extents = Vec3(50, 50, 0.05);
  poses.back().x = Vec3(0, 0, -0.05);
  poses.back().R.setIdentity();
  const WorldModel model(models, WorldParams{});
  SweepAndPrune sweep;
  std::vector<BodyPair> out;
  for (auto _ : state) {
    if (state.range(1))
      sweep.pairs(model, poses, 0.01, out);
    else
      all_pairs(model, poses, 0.01, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["pairs"] = static_cast<double>(out.size());
}
BENCHMARK(BM_BroadPhase_Grid)->ArgsProduct({{8, 32, 128}, {0, 1}})->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace wysiwyf::haptics
