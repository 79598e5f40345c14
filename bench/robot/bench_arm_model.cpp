// The generic arm model (ArmModel on KDL) per arm: forward kinematics, Jacobian, inverse
// kinematics (every solution, and the nearest within limits), RNEA, mass matrix and forward
// dynamics, over 1024 random configurations within the joint limits (cycled). For the PUMA 560
// the same calls of its closed-form PumaModel run in this binary (bench_robot.cpp), the peer
// the generic model is compared with; the PUMA's ArmModel with its numerical IK shows what the
// closed form saves. Counter allocs_per_call: operator new calls per call (none on hot calls).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../common/per_call.hpp"
#include "arm_model/arm_model.hpp"

namespace {

using wysiwyf::robot::ArmModel;
using wysiwyf::robot::JointVector;

constexpr std::size_t kPoses = 1024;

struct ArmFixture {
  std::unique_ptr<ArmModel> model;
  std::vector<JointVector> q, qd, qdd;
  std::vector<Eigen::Isometry3d> base_T_tip;

  ArmFixture(const std::string& urdf, bool numerical) {
    model = std::make_unique<ArmModel>(std::string(WYSIWYF_CONFIG_DIR) + "/robots/" + urdf, "flange");
    if (numerical) model->use_numerical_ik();
    const int n = model->dof();
    std::mt19937_64 rng(42);
    for (std::size_t k = 0; k < kPoses; ++k) {
      JointVector a(n), b(n), c(n);
      for (int j = 0; j < n; ++j) {
        const double lo = std::isfinite(model->limits().lower[j]) ? model->limits().lower[j] : -M_PI;
        const double hi = std::isfinite(model->limits().upper[j]) ? model->limits().upper[j] : M_PI;
        a[j] = std::uniform_real_distribution<double>(lo, hi)(rng);
        b[j] = std::uniform_real_distribution<double>(-2.0, 2.0)(rng);
        c[j] = std::uniform_real_distribution<double>(-5.0, 5.0)(rng);
      }
      q.push_back(a);
      qd.push_back(b);
      qdd.push_back(c);
      base_T_tip.push_back(model->fk(a));
    }
  }
};

// One fixture per arm and IK method, built on first use.
ArmFixture& fixture(const std::string& urdf, bool numerical = false) {
  static std::map<std::string, std::unique_ptr<ArmFixture>> fixtures;
  auto& f = fixtures[urdf + (numerical ? "/numerical" : "")];
  if (!f) f = std::make_unique<ArmFixture>(urdf, numerical);
  return *f;
}

// Runs `call(i)` over the poses; reports allocations per call.
template <typename Call>
void run(benchmark::State& state, Call call) {
  wysiwyf::bench::run_per_call(state, kPoses, call);
}

void BM_ArmForwardKinematics(benchmark::State& state, const char* urdf) {
  ArmFixture& f = fixture(urdf);
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model->fk(f.q[i])); });
}

void BM_ArmJacobian(benchmark::State& state, const char* urdf) {
  ArmFixture& f = fixture(urdf);
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model->jacobian(f.q[i])); });
}

// Every solution from the next pose's joints as reference (a 2 pi representative, the numerical
// IK's first seed).
void BM_ArmInverseKinematicsAll(benchmark::State& state, const char* urdf, bool numerical) {
  ArmFixture& f = fixture(urdf, numerical);
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model->ik(f.base_T_tip[i], f.q[(i + 1) % kPoses])); });
}

// The nearest solution to a configuration 0.05 rad away on every joint: the display's case (the
// arm tracks a setpoint near where it is).
void BM_ArmInverseKinematicsNearest(benchmark::State& state, const char* urdf, bool numerical) {
  ArmFixture& f = fixture(urdf, numerical);
  std::vector<JointVector> near;
  for (const JointVector& q : f.q) near.push_back((q.array() + 0.05).matrix());
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model->ik_nearest(f.base_T_tip[i], near[i])); });
}

void BM_ArmRnea(benchmark::State& state, const char* urdf) {
  ArmFixture& f = fixture(urdf);
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model->rnea(f.q[i], f.qd[i], f.qdd[i])); });
}

void BM_ArmMassMatrix(benchmark::State& state, const char* urdf) {
  ArmFixture& f = fixture(urdf);
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model->mass_matrix(f.q[i])); });
}

void BM_ArmForwardDynamics(benchmark::State& state, const char* urdf) {
  ArmFixture& f = fixture(urdf);
  run(state, [&](std::size_t i) { benchmark::DoNotOptimize(f.model->forward_dynamics(f.q[i], f.qd[i], f.qdd[i])); });
}

#define WYSIWYF_ARM_BENCHMARKS(arm, urdf)                              \
  BENCHMARK_CAPTURE(BM_ArmForwardKinematics, arm, urdf);               \
  BENCHMARK_CAPTURE(BM_ArmJacobian, arm, urdf);                        \
  BENCHMARK_CAPTURE(BM_ArmInverseKinematicsAll, arm, urdf, false);     \
  BENCHMARK_CAPTURE(BM_ArmInverseKinematicsNearest, arm, urdf, false); \
  BENCHMARK_CAPTURE(BM_ArmRnea, arm, urdf);                            \
  BENCHMARK_CAPTURE(BM_ArmMassMatrix, arm, urdf);                      \
  BENCHMARK_CAPTURE(BM_ArmForwardDynamics, arm, urdf)

WYSIWYF_ARM_BENCHMARKS(puma560, "puma560.urdf");
WYSIWYF_ARM_BENCHMARKS(ur5e, "ur5e.urdf");
WYSIWYF_ARM_BENCHMARKS(fr3, "fr3.urdf");
BENCHMARK_CAPTURE(BM_ArmInverseKinematicsAll, puma560_numerical, "puma560.urdf", true);
BENCHMARK_CAPTURE(BM_ArmInverseKinematicsNearest, puma560_numerical, "puma560.urdf", true);
BENCHMARK_CAPTURE(BM_ArmInverseKinematicsNearest, ur5e_numerical, "ur5e.urdf", true);

}  // namespace
