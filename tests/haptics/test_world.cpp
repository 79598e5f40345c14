// The rigid-body world against physical truths: analytic motion, conservation laws, resting,
// restitution, pushes and walls. All on simulated time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

constexpr double g = 9.81;

BodyModel cube(double mass = 1.0, double restitution = 0.0, double half = 0.1) {
  BodyModel m;
  m.name = "cube";
  m.half_extents = Vec3::Constant(half);
  m.mass = mass;
  m.inertia_body = BodyModel::box_inertia(mass, m.half_extents);
  m.restitution = restitution;
  return m;
}

// A static table whose top face is z = 0.
BodyModel table(double restitution = 1.0) {
  BodyModel m;
  m.name = "table";
  m.dynamic = false;
  m.half_extents = Vec3(2.0, 2.0, 0.05);
  m.restitution = restitution;
  return m;
}
BodyState at(const Vec3& x, const Vec3& velocity = Vec3::Zero(), double mass = 1.0) {
  BodyState s;
  s.x = x;
  s.P = mass * velocity;
  return s;
}

TEST(World, FreeFallMatchesTheAnalyticSolution) {
  World w({cube()}, {at(Vec3(0, 0, 1.0))});
  for (int i = 0; i < 1000; ++i) w.step(1e-3);
  EXPECT_NEAR(w.time(), 1.0, 1e-12);
  EXPECT_NEAR(w.state(0).x.z(), 1.0 - 0.5 * g * 1.0, 1e-6);
  EXPECT_NEAR(w.kinematics(0).v.z(), -g, 1e-6);
}

TEST(World, ProjectileMatchesTheAnalyticSolution) {
  const Vec3 v0(2.0, -1.0, 5.0);
  World w({cube()}, {at(Vec3(0, 0, 0), v0)});
  for (int i = 0; i < 800; ++i) w.step(1e-3);
  const double t = 0.8;
  const Vec3 expected(v0.x() * t, v0.y() * t, v0.z() * t - 0.5 * g * t * t);
  EXPECT_LE((w.state(0).x - expected).norm(), 1e-6);
}

TEST(World, ATorqueFreeTumblingBoxConservesEnergyAndAngularMomentum) {
  BodyModel box = cube();
  box.half_extents = Vec3(0.1, 0.05, 0.02);
  box.inertia_body = BodyModel::box_inertia(1.0, box.half_extents);
  BodyState s;
  s.L = Vec3(0.001, 0.02, 0.0005);  // near the intermediate axis: it tumbles (Dzhanibekov)
  WorldParams p;
  p.gravity.setZero();
  p.rtol = 1e-12;
  p.atol = 1e-14;
  World w({box}, {s}, p);
  const double e0 = w.energy();
  const Vec3 L0 = w.state(0).L;
  double max_energy_drift = 0;
  Quat q_start = w.state(0).q;
  double max_turn = 0;
  for (int i = 0; i < 10000; ++i) {
    w.step(1e-3);
    max_energy_drift = std::max(max_energy_drift, std::abs(w.energy() - e0) / e0);
    max_turn = std::max(max_turn, w.state(0).q.angularDistance(q_start));
  }
  EXPECT_GT(max_turn, 2.0);  // it really tumbled
  EXPECT_LE(max_energy_drift, 1e-6);
  EXPECT_LE((w.state(0).L - L0).norm() / L0.norm(), 1e-6);
}

// Lowest corner height of body 0 above the table top.
double lowest_corner(const World& w) {
  const auto k = w.kinematics(0);
  double z = 1e9;
  for (int i = 0; i < 8; ++i)
    z = std::min(z, (w.state(0).x + k.R * BoxTopology::corner(w.model(0).half_extents, i)).z());
  return z;
}

// (Sleeping off: the integration's own rest; test_sleeping.cpp has the cube asleep.)
TEST(World, ACubeDropped5cmComesToRestWithoutSinkingOrDrifting) {
  // Slightly tilted so the corners land one after another.
  BodyState s = at(Vec3(0, 0, 0.1 + 0.05 + 0.02));
  s.q = Quat(Eigen::AngleAxisd(0.15, Vec3(1, 0.5, 0).normalized()));
  WorldParams p;
  p.sleep_after = 0;
  World w({cube(1.0, 0.3), table()}, {s, at(Vec3(0, 0, -0.05))}, p);
  double deepest = 0;
  for (int i = 0; i < 3000; ++i) {
    w.step(1e-3);
    deepest = std::min(deepest, lowest_corner(w));
  }
  EXPECT_GE(deepest, -1e-4) << "penetrated while landing";
  EXPECT_LT(w.kinematics(0).v.norm(), 1e-4) << "not at rest after 3 s";
  const Vec3 rest = w.state(0).x;
  EXPECT_NEAR(rest.z(), 0.1, 1e-4);
  double drift = 0;
  for (int i = 0; i < 60000; ++i) {
    w.step(1e-3);
    drift = std::max(drift, (w.state(0).x - rest).norm());
    deepest = std::min(deepest, lowest_corner(w));
  }
  EXPECT_LE(drift, 1e-4) << "drifted over 60 s";
  EXPECT_GE(deepest, -1e-4) << "sank while resting";
  double weight = 0;
  for (const auto& c : w.resting_contacts()) weight += c.force;
  EXPECT_NEAR(weight, g, 1e-3) << "the table carries the cube's weight";
}

// (With either integrator: each finds the impacts on its own dense output.)
TEST(World, BounceApexHeightsFallByRestitutionSquared) {
  for (const Integrator integrator : {Integrator::kRungeKutta, Integrator::kAdams}) {
    const double e = 0.8, h0 = 0.2;
    WorldParams p;
    p.integrator = integrator;
    World w({cube(1.0, e), table()}, {at(Vec3(0, 0, 0.1 + h0)), at(Vec3(0, 0, -0.05))}, p);
    std::vector<double> apexes;
    double prev_vz = 0, deepest = 0;
    for (int i = 0; i < 3000 && apexes.size() < 4; ++i) {
      w.step(1e-3);
      EXPECT_NEAR(w.time(), (i + 1) * 1e-3, 1e-12) << "a step is its dt, impacts or not";
      deepest = std::min(deepest, lowest_corner(w));
      const double vz = w.kinematics(0).v.z();
      if (prev_vz > 0 && vz <= 0) apexes.push_back(lowest_corner(w));  // sampled at 1 ms: error < g dt^2 / 8
      prev_vz = vz;
    }
    ASSERT_GE(apexes.size(), 3u);
    double previous = h0;
    for (double apex : apexes) {
      EXPECT_NEAR(apex / previous, e * e, 0.01 * e * e) << "apex " << apex << " after " << previous;
      previous = apex;
    }
    EXPECT_GE(deepest, -1e-9) << "the impacts are found where the corners meet the table";
  }
}

TEST(World, AConstantPushOnAFrictionlessTableGivesFOverM) {
  const double m = 2.0;
  const Vec3 F(3.0, 1.0, 0.0);
  World w({cube(m), table()}, {at(Vec3(0, 0, 0.1), Vec3::Zero(), m), at(Vec3(0, 0, -0.05))});
  for (int i = 0; i < 100; ++i) w.step(1e-3);  // settle
  const Vec3 x0 = w.state(0).x;
  w.set_external_wrench(0, F, Vec3::Zero());
  for (int i = 0; i < 1000; ++i) w.step(1e-3);
  const Vec3 expected = x0 + 0.5 * F / m * 1.0;
  EXPECT_NEAR(w.state(0).x.x(), expected.x(), 1e-6);
  EXPECT_NEAR(w.state(0).x.y(), expected.y(), 1e-6);
  EXPECT_NEAR(w.state(0).x.z(), 0.1, 1e-6);
  EXPECT_NEAR(w.kinematics(0).v.x(), F.x() / m, 1e-6);
}

// The haptic display's accuracy: a new sensor sample every 1 ms (a slow sway plus noise, held
// until the next one), the cube on a frictionless table, at the tolerance admittance_sim uses.
// Its horizontal motion is exact by hand (each sample a constant acceleration for 1 ms).
TEST(World, ANoisySampledPushFollowsTheExactZeroOrderHoldMotionAtTheHapticTolerance) {
  for (const Integrator integrator : {Integrator::kRungeKutta, Integrator::kAdams}) {
    WorldParams p;
    p.rtol = kHapticRtol;
    p.atol = 1e-2 * kHapticRtol;
    p.integrator = integrator;
    World w({cube(), table()}, {at(Vec3(0, 0, 0.1)), at(Vec3(0, 0, -0.05))}, p);
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0, 0.05);
    const double h = 1e-3;
    Eigen::Vector2d x = Eigen::Vector2d::Zero(), v = Eigen::Vector2d::Zero();
    double worst = 0;
    for (int k = 0; k < 10000; ++k) {
      const Eigen::Vector2d f(0.2 * std::sin(3.0 * k * h) + noise(rng), noise(rng));
      w.set_external_wrench(0, Vec3(f.x(), f.y(), noise(rng)), Vec3::Zero());
      w.step(h);
      x += v * h + 0.5 * f * h * h;  // m = 1 kg
      v += f * h;
      worst = std::max(worst, (w.state(0).x.head<2>() - x).norm());
    }
    const bool adams = integrator == Integrator::kAdams;
    std::printf("[measured] %s: worst position error over 10 s %.3g um\n", adams ? "Adams" : "Runge-Kutta",
                worst * 1e6);
    EXPECT_GT(std::abs(x.x()), 0.5);  // it really travelled
    // Adams restarted at order 1 every sample: 4.4 um. Runge-Kutta 3(2) integrates each sample's
    // quadratic exactly: 2.4e-7 um, round-off.
    EXPECT_LE(worst, adams ? 1e-5 : 1e-8);
    EXPECT_NEAR(w.state(0).x.z(), 0.1, 1e-9);
  }
}

TEST(World, ACubePushedIntoAWallStopsWithoutPenetrating) {
  BodyModel wall;
  wall.name = "wall";
  wall.dynamic = false;
  wall.half_extents = Vec3(0.05, 1.0, 0.5);
  wall.restitution = 0.0;
  // Wall face at x = 0.5; the cube's face starts at x = 0.1. The wall stands 1 cm into the table
  // (a face exactly on the table's top would be a second floor for the cube's corners).
  World w({cube(1.0, 0.0), table(), wall}, {at(Vec3(0, 0, 0.1)), at(Vec3(0, 0, -0.05)), at(Vec3(0.55, 0, 0.49))});
  w.set_external_wrench(0, Vec3(5.0, 0, 0), Vec3::Zero());
  double max_face = -1;
  for (int i = 0; i < 2000; ++i) {
    w.step(1e-3);
    max_face = std::max(max_face, w.state(0).x.x() + 0.1);
  }
  EXPECT_LE(max_face, 0.5 + 1e-4) << "went into the wall";
  EXPECT_NEAR(w.state(0).x.x() + 0.1, 0.5, 1e-4) << "stopped at the wall";
  EXPECT_LT(w.kinematics(0).v.norm(), 1e-4);
  double wall_force = 0;
  for (const auto& c : w.resting_contacts())
    if (c.feature.b == 2 || c.feature.a == 2) wall_force += c.force;
  EXPECT_NEAR(wall_force, 5.0, 1e-3) << "the wall pushes back with the push";
}

TEST(World, ACopyOfItsStateGoesOnAsItWouldAndLeavesItUntouched) {
  BodyModel wall;
  wall.name = "wall";
  wall.dynamic = false;
  wall.half_extents = Vec3(0.05, 1.0, 0.5);
  // The cube's face 5 cm from the wall's (x = 0.5), pushed with 1 N: it meets the wall after
  // sqrt(2 0.05 / 1) = 316 ms at 0.32 m/s.
  const std::vector<BodyModel> models{cube(1.0, 0.0), table(), wall};
  const std::vector<BodyState> initial{at(Vec3(0.35, 0, 0.1)), at(Vec3(0, 0, -0.05)), at(Vec3(0.55, 0, 0.49))};
  World w(models, initial), reference(models, initial), ahead(models, initial);
  for (World* x : {&w, &reference}) x->set_external_wrench(0, Vec3(1.0, 0, 0), Vec3::Zero());
  for (int i = 0; i < 200; ++i) w.step(1e-3), reference.step(1e-3);
  EXPECT_FALSE(w.watching(0)) << "3 cm from the wall, more than the margin";
  for (int i = 0; i < 90; ++i) w.step(1e-3), reference.step(1e-3);
  EXPECT_TRUE(w.watching(0)) << "8 mm from the wall, within the margin";
  ahead.copy_state_from(w);
  EXPECT_EQ(ahead.time(), w.time());
  for (int i = 0; i < 40; ++i) ahead.step(1e-3);  // across the impact
  for (int i = 0; i < 40; ++i) w.step(1e-3), reference.step(1e-3);
  EXPECT_NEAR(w.state(0).x.x() + 0.1, 0.5, 1e-4) << "stopped at the wall";
  EXPECT_NEAR(ahead.state(0).x.x(), w.state(0).x.x(), 1e-7) << "the look-ahead saw the same impact";
  EXPECT_EQ(w.state(0).x, reference.state(0).x) << "copying from it changed nothing of it";
  EXPECT_EQ(w.state(0).P, reference.state(0).P);
  World other({cube()}, {at(Vec3(0, 0, 1))});
  EXPECT_THROW(other.copy_state_from(w), std::invalid_argument);
}

// A corner that crosses a face near its rim and is past the rim by the end of the integrator's
// step: its gap, open at the step's start, is "not facing" at the end, yet it hit in between.
// A box tilted on one edge flies at 5 m/s over the edge of a small table, its lowest corners
// 0.2 mm above the top face and sinking at 0.5 m/s: they reach the face 0.4 ms in, 2 mm inside
// its rim, and would be 1 mm past it by the step's end. They bounce off the face there by the
// restitution law (found only once the rim was crossed, the corner went on 0.15 mm below the face's
// plane and left it at 0.27 m/s).
TEST(World, ACornerThatHitsAFaceAndWouldLeaveItWithinTheStepBouncesOffIt) {
  constexpr double kRestitution = 0.5, kSinking = 0.5;
  BodyModel box = cube(0.2, kRestitution, 0.02);
  BodyModel small_table = table(kRestitution);
  small_table.half_extents = Vec3(0.05, 0.05, 0.05);  // top face z = 0, x and y within +-5 cm
  BodyState s;
  s.q = Quat(Eigen::AngleAxisd(0.1, Vec3::UnitY()));  // the +x bottom edge lowest
  const Vec3 corner_in_box(0.02, 0.02, -0.02);
  s.x = Vec3(0.046, 0, 2e-4) - s.q * Vec3(0.02, 0, -0.02);
  s.P = 0.2 * Vec3(5.0, 0, -kSinking);
  World w({box, small_table}, {s, at(Vec3(0, 0, -0.05))});
  const StepReport r = w.step(1e-3);
  EXPECT_EQ(r.collisions, 1);
  const BodyKinematics k = w.kinematics(0);
  const Vec3 corner = w.state(0).x + w.state(0).q * corner_in_box;
  EXPECT_GT(corner.x(), 0.05) << "past the rim";
  EXPECT_GT(corner.z(), 0) << "above the face it hit";
  // (the corner's speed after the impact, changed by gravity and the box's spin over 0.6 ms by about 1 %)
  EXPECT_NEAR((k.v + k.omega.cross(corner - w.state(0).x)).z(), kRestitution * kSinking, 0.01 * kSinking);
}
}  // namespace wysiwyf::haptics
