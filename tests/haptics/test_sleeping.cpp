// Sleeping islands (WorldParams::sleep_after): bodies at rest leave the integration and come back
// when pushed, hit or left unsupported, moving then as if they had never slept. Each world here
// runs beside one that never sleeps. All on simulated time.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

namespace {

constexpr double g = 9.81;

BodyModel box(const char* name, double mass, double half, double restitution = 0, double friction = 0) {
  BodyModel m;
  m.name = name;
  m.half_extents = Vec3::Constant(half);
  m.mass = mass;
  m.inertia_body = BodyModel::box_inertia(mass, m.half_extents);
  m.restitution = restitution;
  m.friction = friction;
  return m;
}

BodyModel table(double friction = 0) {
  BodyModel m = box("table", 1, 0);
  m.dynamic = false;
  m.half_extents = Vec3(2.0, 2.0, 0.05);
  m.friction = friction;
  return m;
}

BodyState at(const Vec3& x, const Vec3& momentum = Vec3::Zero()) {
  BodyState s;
  s.x = x;
  s.P = momentum;
  return s;
}

WorldParams never_sleeping() {
  WorldParams p;
  p.sleep_after = 0;
  return p;
}

}  // namespace

TEST(Sleeping, ACubeAtRestSleepsDoesNoWorkAndAPushMovesItAsIfItHadNeverSlept) {
  const std::vector<BodyModel> models = {box("cube", 2.0, 0.05), table()};
  const std::vector<BodyState> initial = {at(Vec3(0, 0, 0.05)), at(Vec3(0, 0, -0.05))};
  World sleeping(models, initial), awake(models, initial, never_sleeping());
  StepReport r;
  for (int k = 0; k < 200; ++k) r = sleeping.step(1e-3), awake.step(1e-3);
  ASSERT_TRUE(sleeping.asleep(0)) << "still for 0.2 s";
  EXPECT_FALSE(awake.asleep(0));
  EXPECT_EQ(r.bodies_asleep, 1);
  EXPECT_EQ(r.rhs_evaluations, 0) << "a sleeping world evaluates nothing";
  EXPECT_EQ(r.integrator_steps, 0);
  EXPECT_NEAR((sleeping.state(0).x - awake.state(0).x).norm(), 0, 1e-12);
  ASSERT_EQ(sleeping.resting_contacts().size(), 4u);
  double carried = 0;
  for (const auto& c : sleeping.resting_contacts()) carried += c.force;
  EXPECT_NEAR(carried, 2.0 * g, 1e-9) << "the sleeping cube's contacts still carry its weight";

  const Vec3 F(2.0, 1.0, 0.0);
  sleeping.set_external_wrench(0, F, Vec3::Zero());
  awake.set_external_wrench(0, F, Vec3::Zero());
  for (int k = 0; k < 500; ++k) {
    sleeping.step(1e-3), awake.step(1e-3);
    ASSERT_FALSE(sleeping.asleep(0)) << "pushed, at step " << k;
  }
  EXPECT_NEAR((sleeping.state(0).x - awake.state(0).x).norm(), 0, 1e-9);
  EXPECT_NEAR((sleeping.state(0).P - awake.state(0).P).norm(), 0, 1e-9);
  const Vec3 expected = initial[0].x + 0.5 * F / 2.0 * 0.5 * 0.5;
  EXPECT_NEAR((sleeping.state(0).x - expected).norm(), 0, 1e-6);
}

// Box B, pushed and let go, slides into box A asleep on a frictionless table: A wakes at the
// impact, which conserves momentum and follows the restitution law as with A awake.
TEST(Sleeping, ASleepingBoxHitByAnotherWakesAndTheImpactKeepsTheRestitutionLaw) {
  const double e = 0.5, ma = 1.0, mb = 0.5;
  const std::vector<BodyModel> models = {box("a", ma, 0.05, e), box("b", mb, 0.05, e), table()};
  const std::vector<BodyState> initial = {at(Vec3(0, 0, 0.05)), at(Vec3(-0.2, 0, 0.05)), at(Vec3(0, 0, -0.05))};
  World sleeping(models, initial), awake(models, initial, never_sleeping());
  for (int k = 0; k < 100; ++k) sleeping.step(1e-3), awake.step(1e-3);
  ASSERT_TRUE(sleeping.asleep(0) && sleeping.asleep(1));
  for (World* w : {&sleeping, &awake}) w->set_external_wrench(1, Vec3(1.0, 0, 0), Vec3::Zero());
  for (int k = 0; k < 100; ++k) sleeping.step(1e-3), awake.step(1e-3);
  for (World* w : {&sleeping, &awake}) w->set_external_wrench(1, Vec3::Zero(), Vec3::Zero());
  const double v0 = sleeping.kinematics(1).v.x();
  EXPECT_NEAR(v0, 0.2, 1e-9) << "1 N on 0.5 kg for 0.1 s";
  bool hit = false;
  for (int k = 0; k < 1000 && !hit; ++k) {
    EXPECT_TRUE(sleeping.asleep(0)) << "a, before the impact";
    EXPECT_FALSE(sleeping.asleep(1)) << "b, coasting";
    hit = sleeping.step(1e-3).collisions > 0;
    awake.step(1e-3);
  }
  ASSERT_TRUE(hit);
  EXPECT_FALSE(sleeping.asleep(0)) << "hit";
  const double va = sleeping.kinematics(0).v.x(), vb = sleeping.kinematics(1).v.x();
  EXPECT_NEAR(ma * va + mb * vb, mb * v0, 1e-9) << "momentum";
  EXPECT_NEAR(va - vb, e * v0, 1e-9) << "restitution";
  EXPECT_NEAR(va, awake.kinematics(0).v.x(), 1e-9);
  EXPECT_NEAR(vb, awake.kinematics(1).v.x(), 1e-9);
  for (int k = 0; k < 200; ++k) sleeping.step(1e-3);
  EXPECT_FALSE(sleeping.asleep(0)) << "sliding on";
}

// The bottom box of a two-box stack pushed out from under the top one (everything frictionless):
// the stack is one island, so the push wakes the top box too, and it falls instead of hovering.
TEST(Sleeping, PushingTheBottomBoxOfASleepingStackWakesTheTopOneWhichFalls) {
  const std::vector<BodyModel> models = {box("bottom", 1.0, 0.05), box("top", 0.2, 0.03), table()};
  const std::vector<BodyState> initial = {at(Vec3(0, 0, 0.05)), at(Vec3(0, 0, 0.13)), at(Vec3(0, 0, -0.05))};
  World w(models, initial);
  for (int k = 0; k < 100; ++k) w.step(1e-3);
  ASSERT_TRUE(w.asleep(0) && w.asleep(1));
  w.set_external_wrench(0, Vec3(20.0, 0, 0), Vec3::Zero());
  w.step(1e-3);
  EXPECT_FALSE(w.asleep(1)) << "the top box shares the pushed box's island";
  for (int k = 0; k < 500; ++k) w.step(1e-3);
  EXPECT_LT(w.state(1).x.z(), 0.031) << "the top box on the table, not where the bottom one held it";
  EXPECT_GT(w.state(1).x.z(), 0.0299);
}

// A box sliding to a stop on a table with friction sleeps only once stopped, where it would
// have stopped awake (v^2 / (2 mu g) from where it started).
TEST(Sleeping, ABoxSlidingToAStopSleepsOnlyOnceItHasStopped) {
  const double mu = 0.5, v0 = 0.5;
  const std::vector<BodyModel> models = {box("box", 1.0, 0.05, 0, mu), table(mu)};
  const std::vector<BodyState> initial = {at(Vec3(0, 0, 0.05), Vec3(v0, 0, 0)), at(Vec3(0, 0, -0.05))};
  World sleeping(models, initial), awake(models, initial, never_sleeping());
  const double t_stop = v0 / (mu * g);
  int first_asleep = -1;
  for (int k = 1; k <= 400; ++k) {
    sleeping.step(1e-3), awake.step(1e-3);
    if (sleeping.asleep(0) && first_asleep < 0) first_asleep = k;
    if (k * 1e-3 < t_stop) {
      ASSERT_FALSE(sleeping.asleep(0)) << "still sliding at step " << k;
    }
  }
  ASSERT_GT(first_asleep, 0);
  EXPECT_LE(first_asleep * 1e-3, t_stop + WorldParams{}.sleep_after + 2e-3) << "asleep soon after stopping";
  EXPECT_NEAR(sleeping.state(0).x.x(), v0 * v0 / (2 * mu * g), 1e-6);
  EXPECT_NEAR((sleeping.state(0).x - awake.state(0).x).norm(), 0, 1e-9);
}

}  // namespace wysiwyf::haptics
