// A resting contact's hysteresis (WorldParams::contact_release): a contact touches from
// contact_tolerance in and, once resting, stays until its gap passes contact_release, so that a
// rocking box's corners, lifted a few um and set down again, are closed by the gap feedback
// instead of an impact each time; a held contact that approaches faster than the feedback closes
// is watched again and hits where it touches, as any impact. All on simulated time.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

namespace {

constexpr double g = 9.81;
constexpr double kHalf = 0.05;
constexpr double kMass = 2.0;
constexpr double kRestitution = 0.5;

std::vector<BodyModel> cube_on_table() {
  BodyModel cube;
  cube.name = "cube";
  cube.half_extents = Vec3::Constant(kHalf);
  cube.mass = kMass;
  cube.inertia_body = BodyModel::box_inertia(kMass, cube.half_extents);
  cube.restitution = kRestitution;
  BodyModel table;
  table.name = "table";
  table.dynamic = false;
  table.half_extents = Vec3(2.0, 2.0, 0.05);
  table.restitution = kRestitution;
  return {cube, table};
}

std::vector<BodyState> resting() {
  std::vector<BodyState> s(2);
  s[0].x = Vec3(0, 0, kHalf);
  s[1].x = Vec3(0, 0, -0.05);
  return s;
}

// The cube turned about its bottom edge at y = -kHalf so that the opposite edge is `lift` up.
BodyState tilted(double lift) {
  const double angle = std::asin(lift / (2 * kHalf));
  const Eigen::AngleAxisd turn(angle, Vec3::UnitX());
  const Vec3 hinge(0, -kHalf, 0);
  BodyState s;
  s.q = Eigen::Quaterniond(turn);
  s.x = hinge + turn * (Vec3(0, 0, kHalf) - hinge);
  return s;
}

double lowest_corner(const World& w) {
  const BodyState& s = w.state(0);
  double lowest = 1;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner(i & 1 ? kHalf : -kHalf, i & 2 ? kHalf : -kHalf, i & 4 ? kHalf : -kHalf);
    lowest = std::min(lowest, (s.x + s.q * corner).z());
  }
  return lowest;
}

struct Settled {
  int impacts = 0;
  double deepest = 0;  // m below the table, over the whole run
  double tilt = 0;     // rad, at the end
};

// The cube rests for 0.1 s, is tilted by `lift` with its contacts as they were, and is let go.
Settled let_go_tilted(double lift, const WorldParams& params) {
  World w(cube_on_table(), resting(), params);
  for (int k = 0; k < 100; ++k) w.step(1e-3);
  EXPECT_EQ(w.resting_contacts().size(), 4u);
  w.set_state(0, tilted(lift));
  Settled out;
  for (int k = 0; k < 500; ++k) {
    out.impacts += w.step(1e-3).collisions;
    out.deepest = std::max(out.deepest, -lowest_corner(w));
  }
  out.tilt = Eigen::AngleAxisd(w.state(0).q).angle();
  return out;
}

}  // namespace

TEST(ContactHysteresis, ACornerLiftedWithinTheReleaseIsSetDownByTheGapFeedbackNotAnImpact) {
  WorldParams p;
  ASSERT_GT(p.contact_release, 2e-5) << "the lift below is within the release";
  const Settled held = let_go_tilted(2e-5, p);
  EXPECT_EQ(held.impacts, 0) << "the lifted corners kept their contacts";
  EXPECT_LT(held.deepest, 1e-6);
  EXPECT_LT(held.tilt, 1e-6) << "back flat on the table";

  // The control: without the hysteresis the corners, 20 um up, are apart; they fall back at
  // 17 mm/s, faster than resting_speed, and bounce.
  p.contact_release = p.contact_tolerance;
  const Settled watched = let_go_tilted(2e-5, p);
  EXPECT_GE(watched.impacts, 2) << "an impact and a bounce";
  EXPECT_LT(watched.deepest, 1e-6);
}

TEST(ContactHysteresis, AHeldContactApproachingFasterThanTheFeedbackClosesHitsWhereItTouches) {
  // Resting, then 20 um up (within the release) and moving down at 5 cm/s: held, the gap feedback
  // would stop it 20 um up, without restitution. It is watched instead, falls to the table and
  // bounces there, exactly as without the hysteresis.
  WorldParams without;
  without.contact_release = without.contact_tolerance;
  World w(cube_on_table(), resting()), control(cube_on_table(), resting(), without);
  for (int k = 0; k < 100; ++k) w.step(1e-3), control.step(1e-3);
  ASSERT_EQ(w.resting_contacts().size(), 4u);
  BodyState s = w.state(0);
  s.x.z() += 2e-5;
  s.P = Vec3(0, 0, kMass * -0.05);
  w.set_state(0, s);
  control.set_state(0, s);
  const StepReport r = w.step(1e-3);
  control.step(1e-3);
  EXPECT_EQ(r.collisions, 1);
  EXPECT_GT(w.state(0).P.z(), 0) << "bounced";
  // Stopped where it was, it would be 20 um up plus its rise since: it fell to the table first.
  EXPECT_LT(w.state(0).x.z() - kHalf, 2e-5);
  EXPECT_NEAR((w.state(0).x - control.state(0).x).norm(), 0, 1e-12);
  EXPECT_NEAR((w.state(0).P - control.state(0).P).norm(), 0, 1e-12);
}

TEST(ContactHysteresis, AReleaseBelowTheToleranceIsRefused) {
  WorldParams p;
  p.contact_release = 0.5 * p.contact_tolerance;
  EXPECT_THROW(World(cube_on_table(), resting(), p), std::invalid_argument);
}

}  // namespace wysiwyf::haptics
