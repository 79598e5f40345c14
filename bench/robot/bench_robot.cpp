// PUMA 560 model benchmarks: forward kinematics, Jacobian, closed-form IK (all 8 and nearest),
// damped least squares step, RNEA, mass matrix and forward dynamics, each over 1024 random
// configurations within the joint limits (cycled, so branches are not learnt from one pose).
// Counter allocs_per_call: operator new calls per call (the hot calls must make none).
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>
#include <random>
#include <vector>

#include "../common/per_call.hpp"
#include "arm_joint_sim/drive_params.hpp"
#include "puma_model/puma_model.hpp"
#include "../common/smoke.hpp"

namespace {

using wysiwyf::robot::PumaModel;
using wysiwyf::robot::Vector6d;

const std::string kUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf";
const std::string kDrive = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560_drive.yaml";
constexpr std::size_t kPoses = 1024;

struct Fixture {
  PumaModel model{kUrdf};
  std::vector<Vector6d> q, qd, qdd;
  std::vector<Eigen::Isometry3d> base_T_flange;

  Fixture() {
    model.set_rotor_inertia(wysiwyf::robot::load_drive_params(kDrive).reflected_inertia());
    std::mt19937_64 rng(42);
    for (std::size_t n = 0; n < kPoses; ++n) {
      Vector6d a, b, c;
      for (int j = 0; j < 6; ++j) {
        a[j] = std::uniform_real_distribution<double>(model.limits().lower[j], model.limits().upper[j])(rng);
        b[j] = std::uniform_real_distribution<double>(-2.0, 2.0)(rng);
        c[j] = std::uniform_real_distribution<double>(-5.0, 5.0)(rng);
      }
      q.push_back(a);
      qd.push_back(b);
      qdd.push_back(c);
      base_T_flange.push_back(model.fk(a));
    }
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

// Runs `call(i)` over the poses; reports allocations per call.
template <typename Call>
void run(benchmark::State& state, Call call) {
  wysiwyf::bench::run_per_call(state, kPoses, call);
}

void BM_ForwardKinematics(benchmark::State& state) {
  Fixture& f = fixture();
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model.fk(f.q[i])); });
}
BENCHMARK(BM_ForwardKinematics);

void BM_Jacobian(benchmark::State& state) {
  Fixture& f = fixture();
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model.jacobian(f.q[i])); });
}
BENCHMARK(BM_Jacobian);

void BM_InverseKinematicsAll8(benchmark::State& state) {
  Fixture& f = fixture();
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model.ik(f.base_T_flange[i], f.q[(i + 1) % kPoses])); });
}
BENCHMARK(BM_InverseKinematicsAll8);

void BM_InverseKinematicsNearest(benchmark::State& state) {
  Fixture& f = fixture();
  run(state,
      [&](std::size_t i) { benchmark::DoNotOptimize(f.model.ik_nearest(f.base_T_flange[i], f.q[(i + 1) % kPoses])); });
}
BENCHMARK(BM_InverseKinematicsNearest);

void BM_DampedLeastSquaresStep(benchmark::State& state) {
  Fixture& f = fixture();
  run(state, [&](std::size_t i) {
    benchmark::DoNotOptimize(f.model.dls_step(f.q[i], f.base_T_flange[(i + 1) % kPoses], 0.05));
  });
}
BENCHMARK(BM_DampedLeastSquaresStep);

void BM_Rnea(benchmark::State& state) {
  Fixture& f = fixture();
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model.rnea(f.q[i], f.qd[i], f.qdd[i])); });
}
BENCHMARK(BM_Rnea);

void BM_MassMatrix(benchmark::State& state) {
  Fixture& f = fixture();
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model.mass_matrix(f.q[i])); });
}
BENCHMARK(BM_MassMatrix);

void BM_ForwardDynamics(benchmark::State& state) {
  Fixture& f = fixture();
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model.forward_dynamics(f.q[i], f.qd[i], f.qdd[i])); });
}
BENCHMARK(BM_ForwardDynamics);

}  // namespace

BENCHMARK_MAIN();
