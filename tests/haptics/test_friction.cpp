// Coulomb friction against physical truths: a push below mu m g does not move a cube, one above
// it accelerates it by (F - mu m g) / m; a sliding cube stops after v0^2 / (2 mu g) and stays;
// on a slope flatter than atan(mu) a cube stays, on a steeper one it slides down with
// g (sin - mu cos); an oblique impact keeps no tangential velocity when friction suffices.
// All on simulated time.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "rigid_body/friction.hpp"
#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {
namespace {

constexpr double g = 9.81;

BodyModel cube(double mass, double mu) {
  BodyModel m;
  m.name = "cube";
  m.half_extents = Vec3::Constant(0.1);
  m.mass = mass;
  m.inertia_body = BodyModel::box_inertia(mass, m.half_extents);
  m.friction = mu;
  return m;
}

BodyModel floor_box(double mu = 0.0) {
  BodyModel m;
  m.name = "floor";
  m.dynamic = false;
  m.half_extents = Vec3(3.0, 3.0, 0.05);
  m.friction = mu;
  return m;
}

// The contact rows of a cube of half-size h on its four bottom corners, on its six velocities:
// each corner's normal (z) in rows 0-3, then its tangents (x, y) in rows 4 + 2i and 4 + 2i + 1.
Eigen::MatrixXd corner_jacobian(double h) {
  const std::array<Vec3, 4> corners = {Vec3(h, h, -h), Vec3(-h, h, -h), Vec3(-h, -h, -h), Vec3(h, -h, -h)};
  const std::array<Vec3, 3> dirs = {Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY()};
  Eigen::MatrixXd J(12, 6);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      const int row = k == 0 ? i : 4 + 2 * i + (k - 1);
      J.row(row) << dirs[k].transpose(), corners[i].cross(dirs[k]).transpose();
    }
  return J;
}

// A = J M^-1 J^T for one body of mass m and inertia (a cube's: the same about every axis).
Eigen::MatrixXd contact_matrix(const Eigen::MatrixXd& J, double m, double inertia) {
  Eigen::VectorXd inv_mass(6);
  inv_mass << Vec3::Constant(1 / m), Vec3::Constant(1 / inertia);
  return J * inv_mass.asDiagonal() * J.transpose();
}

BodyState at(const Vec3& x, const Vec3& v = Vec3::Zero(), double mass = 1.0, const Quat& q = Quat::Identity()) {
  BodyState s;
  s.x = x;
  s.q = q;
  s.P = mass * v;
  return s;
}

TEST(Friction, APushBelowMuMgDoesNotMoveTheCube) {
  const double m = 1.0, mu = 0.5;
  World w({cube(m, mu), floor_box()}, {at(Vec3(0, 0, 0.1)), at(Vec3(0, 0, -0.05))});
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  const Vec3 x0 = w.state(0).x;
  w.set_external_wrench(0, Vec3(0.9 * mu * m * g, 0.0, 0.0), Vec3::Zero());  // 90 % of the breakaway force
  int most_rounds = 0;  // of the friction solve, once the push is on
  for (int i = 0; i < 2000; ++i) {
    const StepReport r = w.step(1e-3);
    if (i > 0) most_rounds = std::max(most_rounds, r.friction_rounds);
    EXPECT_EQ(r.friction_unconverged, 0);
  }
  const double moved = (w.state(0).x - x0).head<2>().norm();
  double friction = 0;
  for (const auto& c : w.resting_contacts()) friction += c.friction.x();
  std::printf("[measured] 0.9 mu m g for 2 s: moved %.3g m, friction %.6f N (push %.6f N), at most %d rounds a step\n",
              moved, friction, 0.9 * mu * m * g, most_rounds);
  // The clamped normal contacts' answer to the friction is anticipated (friction.hpp): the
  // sticking solve settles at once instead of converging by 0.6 a round.
  EXPECT_LE(most_rounds, 3);
  EXPECT_LT(moved, 1e-4);
  EXPECT_NEAR(friction, -0.9 * mu * m * g, 1e-2) << "static friction holds the push";
  EXPECT_NEAR(w.state(0).x.z(), 0.1, 1e-5) << "nor sinks";
}

TEST(Friction, APushAboveMuMgAcceleratesByTheDifference) {
  const double m = 2.0, mu = 0.3;
  const double F = 1.5 * mu * m * g;
  World w({cube(m, mu), floor_box()}, {at(Vec3(0, 0, 0.1), Vec3::Zero(), m), at(Vec3(0, 0, -0.05))});
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  w.set_external_wrench(0, Vec3(F, 0, 0), Vec3::Zero());
  for (int i = 0; i < 500; ++i) w.step(1e-3);  // past the start
  const double x1 = w.state(0).x.x(), v1 = w.kinematics(0).v.x();
  for (int i = 0; i < 1000; ++i) w.step(1e-3);
  const double a = (w.kinematics(0).v.x() - v1) / 1.0;
  const double expected = (F - mu * m * g) / m;
  std::printf("[measured] push 1.5 mu m g: a = %.6f m/s^2, expected %.6f\n", a, expected);
  EXPECT_NEAR(a, expected, 1e-3 * expected);
  EXPECT_GT(w.state(0).x.x(), x1);
  EXPECT_NEAR(w.state(0).x.z(), 0.1, 1e-5);
  EXPECT_NEAR(w.kinematics(0).v.y(), 0.0, 1e-9) << "no sideways drift";
}

TEST(Friction, ASlidingCubeStopsAfterV0SquaredOver2MuGAndStays) {
  const double mu = 0.4, v0 = 1.0;
  World w({cube(1.0, 0.0), floor_box(mu)},  // the floor is the rough one this time
          {at(Vec3(0, 0, 0.1), Vec3(v0 * 0.6, v0 * 0.8, 0)), at(Vec3(0, 0, -0.05))});
  for (int i = 0; i < 1000; ++i) w.step(1e-3);  // stops after v0 / (mu g) = 0.255 s
  const double travelled = w.state(0).x.head<2>().norm();
  const double expected = v0 * v0 / (2 * mu * g);
  const Vec3 x_stop = w.state(0).x;
  for (int i = 0; i < 2000; ++i) w.step(1e-3);
  std::printf("[measured] slid %.6f m from 1 m/s (expected %.6f), then moved %.3g m in 2 s\n", travelled, expected,
              (w.state(0).x - x_stop).norm());
  EXPECT_NEAR(travelled, expected, 0.01 * expected);
  EXPECT_NEAR(w.state(0).x.y() / w.state(0).x.x(), 0.8 / 0.6, 1e-6) << "straight along its velocity";
  EXPECT_LT((w.state(0).x - x_stop).norm(), 1e-5);
  EXPECT_LT(w.kinematics(0).v.norm(), 1e-5);
}

// A static slab tilted by `slope` about y, its top face through the origin; the cube resting on it.
struct Slope {
  World w;
  Vec3 down;  // down the slope
  Slope(double slope, double mu)
      : w({cube(1.0, mu), floor_box()}, {at(Quat(Eigen::AngleAxisd(slope, Vec3::UnitY())) * Vec3(0, 0, 0.1 + 1e-7),
                                            Vec3::Zero(), 1.0, Quat(Eigen::AngleAxisd(slope, Vec3::UnitY()))),
                                         at(Quat(Eigen::AngleAxisd(slope, Vec3::UnitY())) * Vec3(0, 0, -0.05),
                                            Vec3::Zero(), 1.0, Quat(Eigen::AngleAxisd(slope, Vec3::UnitY())))}),
        down(Quat(Eigen::AngleAxisd(slope, Vec3::UnitY())) * Vec3(1, 0, 0)) {}
};

TEST(Friction, OnASlopeFlatterThanAtanMuTheCubeStaysAndOnASteeperOneSlides) {
  const double mu = 0.5;
  {
    Slope s(0.8 * std::atan(mu), mu);
    const Vec3 x0 = s.w.state(0).x;
    for (int i = 0; i < 2000; ++i) s.w.step(1e-3);
    const double moved = (s.w.state(0).x - x0).norm();
    std::printf("[measured] slope 0.8 atan(mu): moved %.3g m in 2 s\n", moved);
    EXPECT_LT(moved, 1e-4);
  }
  {
    const double slope = 1.3 * std::atan(mu);
    Slope s(slope, mu);
    for (int i = 0; i < 300; ++i) s.w.step(1e-3);
    const double v1 = s.w.kinematics(0).v.dot(s.down);
    for (int i = 0; i < 500; ++i) s.w.step(1e-3);
    const double a = (s.w.kinematics(0).v.dot(s.down) - v1) / 0.5;
    const double expected = g * (std::sin(slope) - mu * std::cos(slope));
    std::printf("[measured] slope 1.3 atan(mu): a = %.6f m/s^2 down the slope, expected %.6f\n", a, expected);
    EXPECT_NEAR(a, expected, 0.005 * expected);
  }
}

TEST(Friction, AnObliqueLandingKeepsNoTangentialVelocityWhenFrictionSuffices) {
  // A flat cube landing at 1 m/s down and 0.2 m/s sideways, mu = 1: the tangential impulse needed
  // (0.2 m) is below mu times the normal impulse (1 m), so the impact stops it sliding.
  World w({cube(1.0, 1.0), floor_box()}, {at(Vec3(0, 0, 0.15), Vec3(0.2, 0, -1.0)), at(Vec3(0, 0, -0.05))});
  for (int i = 0; i < 200; ++i) w.step(1e-3);
  EXPECT_LT(std::abs(w.kinematics(0).v.x()), 1e-4);
  EXPECT_NEAR(w.state(0).x.z(), 0.1, 1e-4);
}

TEST(Friction, ACubeSlidingOverARestingCubeSlowsByMuGAndLeavesItWhereItWas) {
  // Two 20 cm cubes stacked on a table (mu 0.5 under the lower, 0.3 between them); the upper is
  // launched along +x at 0.5 m/s. It slows at mu g; the lower, whose table can hold twice the
  // drag, stays put.
  const double m = 1.0, mu = 0.3, v0 = 0.5;
  World w({cube(m, mu), cube(m, mu), floor_box(0.5)},
          {at(Vec3(0, 0, 0.1)), at(Vec3(0, 0, 0.3), Vec3(v0, 0, 0)), at(Vec3(0, 0, -0.05))});
  const Vec3 lower0 = w.state(0).x;
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  const double v = w.kinematics(1).v.x();
  const double moved = (w.state(0).x - lower0).norm();
  std::printf("[measured] after 0.1 s: upper at %.6f m/s (expected %.6f), lower moved %.3g m\n", v, v0 - mu * g * 0.1,
              moved);
  EXPECT_NEAR(v, v0 - mu * g * 0.1, 2e-3) << "the upper slows at mu g";
  EXPECT_LT(moved, 1e-5) << "the lower stays where it was";
}

TEST(Friction, ASpinningCubeStopsAndStaysStopped) {
  // A 0.5 kg, 10 cm cube spinning at 1 rad/s about the vertical and sliding at 2.3 mm/s on a
  // mu = 0.4 floor: its corners' friction stops it within 10 ms. Held at mu f_n against the
  // corners' velocity for a whole step, it used to reverse the spin every step and never stop it
  // (0.09 rad/s forever).
  BodyModel small = cube(0.5, 0.4);
  small.half_extents = Vec3::Constant(0.05);
  small.inertia_body = BodyModel::box_inertia(0.5, small.half_extents);
  BodyState spinning = at(Vec3(0, 0, 0.05), Vec3(0.0023, 0, 0), 0.5);
  spinning.L = small.inertia_body * Vec3(0, 0, 1.0);
  World w({small, floor_box(0.4)}, {spinning, at(Vec3(0, 0, -0.05))});
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  EXPECT_LT(w.kinematics(0).omega.norm(), 1e-9);
  EXPECT_LT(w.kinematics(0).v.norm(), 1e-9);
}

TEST(FrictionSolver, TheNormalForcesStayExactAndTheFrictionStaysOnItsDisc) {
  // One contact of a unit point mass on a plane: normal row and two tangent rows decoupled.
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(3, 3);
  LcpSolver lcp;
  FrictionSolver solver;
  Eigen::VectorXd bn(1), bt(2), mu(1);
  bn << -9.81;      // gravity pulls into the plane
  bt << -3.0, 4.0;  // a tangential load of 5
  mu << 0.4;        // can hold 3.924
  const Eigen::VectorXd still = Eigen::VectorXd::Zero(2);
  const FrictionResult r = solver.solve(lcp, A, bn, bt, mu, still);
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.fn[0], 9.81, 1e-12);
  EXPECT_NEAR(r.ft.norm(), 0.4 * 9.81, 1e-12) << "on the rim: sliding";
  EXPECT_NEAR(r.ft[0] / r.ft[1], -3.0 / 4.0, 1e-12) << "against the load";
  mu << 0.6;  // can hold 5.886: sticks, exactly cancelling the load
  const FrictionResult s = solver.solve(lcp, A, bn, bt, mu, still);
  EXPECT_NEAR(s.ft[0], 3.0, 1e-12);
  EXPECT_NEAR(s.ft[1], -4.0, 1e-12);
  Eigen::VectorXd sliding(2);
  sliding << 0.0, -2.0;  // sliding along -t2: friction along +t2 with all it has, whatever the load
  mu << 0.4;
  const FrictionResult d = solver.solve(lcp, A, bn, bt, mu, sliding);
  EXPECT_NEAR(d.ft[0], 0.0, 1e-12);
  EXPECT_NEAR(d.ft[1], 0.4 * 9.81, 1e-12);
}

TEST(FrictionSolver, AFacesFourCornersShareTheNormalLoadAndTheFrictionIsBoundedByEachShare) {
  // A 1 kg, 20 cm cube resting on its four bottom corners (a redundant set: three would hold it),
  // pushed along x at 0.9 mu m g through a point 5 cm above its centre (the front corners carry
  // more). Contact space rows: normal (z) then the tangents (x, y) of each corner; A = J M^-1 J^T.
  const double m = 1.0, h = 0.1, inertia = m * (2 * h) * (2 * h) / 6, mu = 0.5;
  const Eigen::MatrixXd J = corner_jacobian(h);
  const Eigen::MatrixXd A = contact_matrix(J, m, inertia);
  const Vec3 push(0.9 * mu * m * g, 0, 0), at_point(0, 0, 0.05);
  Eigen::VectorXd load(6);  // the body's acceleration under gravity and the push
  load << (push + Vec3(0, 0, -m * g)) / m, at_point.cross(push) / inertia;
  const Eigen::VectorXd b = J * load;
  LcpSolver lcp;
  FrictionSolver solver;
  const FrictionResult r =
      solver.solve(lcp, A, b.head(4), b.tail(8), Eigen::VectorXd::Constant(4, mu), Eigen::VectorXd::Zero(8));
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 2);
  // The next step, started from this friction (World): the first round's friction with the normal
  // forces the corners answer it with is already the answer (friction.hpp), no second round to
  // confirm it, and those forces are exact for it: every corner at zero normal acceleration.
  const FrictionResult next =
      solver.solve(lcp, A, b.head(4), b.tail(8), Eigen::VectorXd::Constant(4, mu), Eigen::VectorXd::Zero(8), r.ft);
  EXPECT_TRUE(next.converged);
  EXPECT_EQ(next.iterations, 1);
  const Eigen::VectorXd forces = (Eigen::VectorXd(12) << next.fn, next.ft).finished();
  EXPECT_LT((A.topRows(4) * forces + b.head(4)).cwiseAbs().maxCoeff(), 1e-9 * g);
  EXPECT_GE(next.fn.minCoeff(), 0.0);
  EXPECT_LT((next.fn - r.fn).cwiseAbs().maxCoeff(), 1e-6);
  std::printf("[measured] normal forces %.4f %.4f %.4f %.4f N, |friction| %.4f %.4f %.4f %.4f N\n", r.fn[0], r.fn[1],
              r.fn[2], r.fn[3], r.ft.segment<2>(0).norm(), r.ft.segment<2>(2).norm(), r.ft.segment<2>(4).norm(),
              r.ft.segment<2>(6).norm());
  // The pivoting alone leaves one corner without force (any split with the same sum and moments
  // moves nothing); the friction solve bounds the friction by the least forces that do the same,
  // the split four equal springs would carry: every corner a share.
  EXPECT_NEAR(r.fn.sum(), m * g, 1e-9);
  for (int i = 0; i < 4; ++i) {
    EXPECT_GT(r.fn[i], 0.1 * m * g / 4) << "corner " << i;
    EXPECT_LE(r.ft.segment<2>(2 * i).norm(), mu * r.fn[i] * (1 + 1e-9)) << "corner " << i;
  }
  EXPECT_NEAR(r.ft(Eigen::seq(0, 7, 2)).sum(), -push.x(), 1e-9) << "static friction holds the push";
  EXPECT_NEAR(r.ft(Eigen::seq(1, 7, 2)).sum(), 0.0, 1e-9);
  const Eigen::VectorXd front = (Eigen::VectorXd(2) << r.fn[0], r.fn[3]).finished();
  EXPECT_GT(front.minCoeff(), r.fn[1]) << "the push tips the cube onto its front (+x) corners";
}

// What a solve keeps per touching set (its factor, its Schur complement) is the solve's own: a
// solver that has just solved another problem over the same contacts (another cube on the same
// four corners: the same touching set, another Ann) answers exactly as a fresh one.
TEST(FrictionSolver, KeepsNothingOfOneSolvesTouchingSetsForTheNext) {
  const double h = 0.1, mu = 0.5;
  const Eigen::MatrixXd J = corner_jacobian(h);
  const auto problem = [&](double m, double push_height) {
    const double inertia = m * (2 * h) * (2 * h) / 6;
    const Vec3 push(0.9 * mu * m * g, 0.2 * mu * m * g, 0), at_point(0, 0, push_height);
    Eigen::VectorXd load(6);
    load << (push + Vec3(0, 0, -m * g)) / m, at_point.cross(push) / inertia;
    return std::make_pair(contact_matrix(J, m, inertia), Eigen::VectorXd(J * load));
  };
  const auto solve = [&](FrictionSolver& solver, const std::pair<Eigen::MatrixXd, Eigen::VectorXd>& p) {
    LcpSolver lcp;
    return solver.solve(lcp, p.first, p.second.head(4), p.second.tail(8), Eigen::VectorXd::Constant(4, mu),
                        Eigen::VectorXd::Zero(8));
  };
  const auto light = problem(0.3, -0.05), heavy = problem(2.0, 0.05);
  FrictionSolver fresh, used;
  const FrictionResult expected = solve(fresh, heavy);
  ASSERT_TRUE(expected.ok);
  const FrictionResult before = solve(used, light);
  ASSERT_TRUE(before.ok);
  const FrictionResult after = solve(used, heavy);
  ASSERT_TRUE(after.ok);
  EXPECT_EQ(after.iterations, expected.iterations);
  EXPECT_EQ(after.fn, expected.fn) << after.fn.transpose() << " against " << expected.fn.transpose();
  EXPECT_EQ(after.ft, expected.ft) << after.ft.transpose() << " against " << expected.ft.transpose();
  EXPECT_GT((before.fn - expected.fn).cwiseAbs().maxCoeff(), 1.0) << "two problems, not one";
}

// A cube resting alone (most boxes of a pile) takes no friction and no stick solve; the least push
// whose effect is beyond the rounds' tolerance is held exactly, one within it is left to slide (at
// most 1e-8 of the loads: 1e-10 m/s gained in a 1 ms step).
TEST(FrictionSolver, ACubeUnderGravityAloneTakesNoFrictionAndAPushBeyondTheToleranceIsHeld) {
  const double m = 1.0, h = 0.1, inertia = m * (2 * h) * (2 * h) / 6, mu = 0.5;
  const Eigen::MatrixXd J = corner_jacobian(h);
  const Eigen::MatrixXd A = contact_matrix(J, m, inertia);
  LcpSolver lcp;
  FrictionSolver solver;
  const auto solve_pushed = [&](double push) {
    Eigen::VectorXd load(6);
    load << push / m, 0, -g, 0, 0, 0;
    const Eigen::VectorXd b = J * load;
    return solver.solve(lcp, A, b.head(4), b.tail(8), Eigen::VectorXd::Constant(4, mu), Eigen::VectorXd::Zero(8));
  };
  const FrictionResult resting = solve_pushed(0);
  ASSERT_TRUE(resting.ok);
  EXPECT_TRUE(resting.converged);
  EXPECT_EQ(resting.iterations, 1);
  EXPECT_TRUE(resting.ft.isZero(0.0)) << resting.ft.transpose();
  EXPECT_NEAR(resting.fn.sum(), m * g, 1e-12);
  const double beyond = 10 * solver.tolerance * m * g;  // 1e-7 of the weight
  const FrictionResult held = solve_pushed(beyond);
  ASSERT_TRUE(held.ok);
  EXPECT_NEAR(held.ft(Eigen::seq(0, 7, 2)).sum(), -beyond, 1e-12 * m * g) << "static friction holds it";
  const FrictionResult within = solve_pushed(0.1 * solver.tolerance * m * g);
  EXPECT_TRUE(within.converged);
  EXPECT_TRUE(within.ft.isZero(0.0)) << "a push within the tolerance: no friction";
}

TEST(FrictionSolver, ASlidingCubesFrictionIsMuTimesTheNormalForcesItsOwnMomentLeavesEachCorner) {
  // The same cube sliding along +x at 1 m/s: every corner slides, its friction mu f_n against the
  // motion, and that friction's moment about the centre presses the front corners and relieves
  // the back ones, which changes the friction: rounds that took the normal forces as fixed
  // converged by a constant factor each (a pile pushed along: 15-26 rounds a step). The sliders'
  // magnitudes are solved with the normal forces' answer to them: 1 round, then exact.
  const double m = 1.0, h = 0.1, inertia = m * (2 * h) * (2 * h) / 6, mu = 0.5;
  const Eigen::MatrixXd J = corner_jacobian(h);
  const Eigen::MatrixXd A = contact_matrix(J, m, inertia);
  Eigen::VectorXd load(6);  // gravity alone
  load << Vec3(0, 0, -g), Vec3::Zero();
  const Eigen::VectorXd b = J * load;
  Eigen::VectorXd vt(8);
  for (int i = 0; i < 4; ++i) vt.segment<2>(2 * i) << 1.0, 0.0;
  LcpSolver lcp;
  FrictionSolver solver;
  // The tangential target as World sets it: no sliding a 1 ms step on (far beyond the cone).
  const Eigen::VectorXd bt = b.tail(8) + vt / 1e-3;
  const FrictionResult r = solver.solve(lcp, A, b.head(4), bt, Eigen::VectorXd::Constant(4, mu), vt);
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  std::printf("[measured] sliding: normal forces %.4f %.4f %.4f %.4f N in %d round(s)\n", r.fn[0], r.fn[1], r.fn[2],
              r.fn[3], r.iterations);
  const Eigen::VectorXd forces = (Eigen::VectorXd(12) << r.fn, r.ft).finished();
  EXPECT_LT((A.topRows(4) * forces + b.head(4)).cwiseAbs().maxCoeff(), 1e-9 * g) << "the normal forces hold";
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(r.ft[2 * i], -mu * r.fn[i], 1e-9) << "corner " << i << ": mu f_n against the motion";
    EXPECT_NEAR(r.ft[2 * i + 1], 0.0, 1e-12);
  }
  EXPECT_NEAR(r.fn.sum(), m * g, 1e-9);
  // The moment of friction mu m g at the base, h below the centre, carried by the corners' split.
  const double front = r.fn[0] + r.fn[3], back = r.fn[1] + r.fn[2];
  EXPECT_NEAR((front - back) * h, mu * m * g * h, 1e-9) << "friction tips it onto its front corners";
}

TEST(FrictionSolver, ABoxSlidingOnARestingBoxIsHeldBackByMuFnWhileTheTableHoldsTheLowerOne) {
  // Two 1 kg, 20 cm cubes stacked on a table; the upper slides along +x at 1 m/s over the lower,
  // which rests. The upper's four corners slide (mu f_n against the motion), the lower's stick:
  // their friction answers the drag of the upper, and the normal forces of both answer the
  // moments of all of it. The sliders' magnitudes and the stickers' friction are solved together
  // with the normal forces' answer (before: rounds converging by a constant factor each).
  const double m = 1.0, h = 0.1, inertia = m * (2 * h) * (2 * h) / 6, mu = 0.3;
  const std::array<Vec3, 4> corners = {Vec3(h, h, -h), Vec3(-h, h, -h), Vec3(-h, -h, -h), Vec3(h, -h, -h)};
  const std::array<Vec3, 3> dirs = {Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY()};
  // Contacts 0-3: the lower cube's bottom corners on the table; 4-7: the upper cube's bottom
  // corners on the lower's top face (a: upper, b: lower, normal +z). Columns: lower, then upper.
  const int n = 8;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3 * n, 12);
  for (int c = 0; c < n; ++c)
    for (int k = 0; k < 3; ++k) {
      const int row = k == 0 ? c : n + 2 * c + (k - 1);
      const Vec3& r = corners[c % 4];
      if (c < 4) {
        J.block<1, 6>(row, 0) << dirs[k].transpose(), r.cross(dirs[k]).transpose();
      } else {  // on the upper at r, on the lower at r + (0, 0, 2h), opposite
        J.block<1, 6>(row, 6) << dirs[k].transpose(), r.cross(dirs[k]).transpose();
        J.block<1, 6>(row, 0) << -dirs[k].transpose(), -(r + Vec3(0, 0, 2 * h)).cross(dirs[k]).transpose();
      }
    }
  Eigen::VectorXd inv_mass(12);
  inv_mass << Vec3::Constant(1 / m), Vec3::Constant(1 / inertia), Vec3::Constant(1 / m), Vec3::Constant(1 / inertia);
  const Eigen::MatrixXd A = J * inv_mass.asDiagonal() * J.transpose();
  Eigen::VectorXd load(12);  // gravity on both
  load << Vec3(0, 0, -g), Vec3::Zero(), Vec3(0, 0, -g), Vec3::Zero();
  const Eigen::VectorXd b = J * load;
  Eigen::VectorXd vt = Eigen::VectorXd::Zero(2 * n);
  for (int c = 4; c < n; ++c) vt[2 * c] = 1.0;           // the upper slides over the lower
  const Eigen::VectorXd bt = b.tail(2 * n) + vt / 1e-3;  // World's target: no sliding 1 ms on
  // Both ways the rounds can start: every contact asked to stick first (World's friction held
  // through a step), or the fast sliders sliding from the start (World's impacts), where only the
  // lower cube's rows stick and the solve reads S along those rows alone (friction.hpp).
  for (const bool stick_first : {true, false}) {
    SCOPED_TRACE(stick_first ? "every contact asked to stick first" : "the fast sliders sliding from the start");
    LcpSolver lcp;
    FrictionSolver solver;
    solver.stick_first = stick_first;
    const FrictionResult r = solver.solve(lcp, A, b.head(n), bt, Eigen::VectorXd::Constant(n, mu), vt);
    ASSERT_TRUE(r.ok);
    EXPECT_TRUE(r.converged);
    std::printf("[measured] upper corners %.4f %.4f %.4f %.4f N, lower %.4f %.4f %.4f %.4f N, %d round(s)\n", r.fn[4],
                r.fn[5], r.fn[6], r.fn[7], r.fn[0], r.fn[1], r.fn[2], r.fn[3], r.iterations);
    EXPECT_LE(r.iterations, 2);
    const Eigen::VectorXd forces = (Eigen::VectorXd(3 * n) << r.fn, r.ft).finished();
    EXPECT_LT((A.topRows(n) * forces + b.head(n)).cwiseAbs().maxCoeff(), 1e-9 * g) << "the normal forces hold";
    double drag = 0, held = 0;
    for (int c = 0; c < n; ++c) {
      if (c >= 4) {
        EXPECT_NEAR(r.ft[2 * c], -mu * r.fn[c], 1e-9) << "upper corner " << c << ": mu f_n against the motion";
        drag += r.ft[2 * c];
      } else {
        EXPECT_LE(r.ft.segment<2>(2 * c).norm(), mu * r.fn[c] * (1 + 1e-9)) << "lower corner " << c << " sticks";
        held += r.ft[2 * c];
      }
    }
    EXPECT_NEAR(drag, -mu * m * g, 1e-9) << "the upper is dragged back by mu m g";
    EXPECT_NEAR(held, drag, 1e-9) << "the table holds the lower back as the lower holds back the upper";
    // The lower cube's corners do not slide on the table (its friction holds it exactly).
    EXPECT_LT((A.bottomRows(2 * n) * forces + bt).head(8).cwiseAbs().maxCoeff(), 1e-9 * g);
  }
}

// A problem written as tests/haptics/data/*.txt: matrices by name, and the LCP's warm start.
struct FrictionProblem {
  std::map<std::string, Eigen::MatrixXd> m;
  LcpIndices clamped;
};

FrictionProblem read_problem(const std::string& path) {
  std::ifstream in(path);
  FrictionProblem p;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream head(line);
    std::string name;
    if (!(head >> name)) continue;  // (the rest of a matrix's last row)
    if (name == "clamped") {
      std::vector<int> c;
      for (int i; head >> i;) c.push_back(i);
      p.clamped.resize(static_cast<Eigen::Index>(c.size()));
      for (std::size_t i = 0; i < c.size(); ++i) p.clamped[static_cast<Eigen::Index>(i)] = c[i];
      continue;
    }
    Eigen::Index rows = 0, cols = 0;
    head >> rows >> cols;
    Eigen::MatrixXd& x = p.m[name];
    x.resize(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i)
      for (Eigen::Index j = 0; j < cols; ++j) in >> x(i, j);
  }
  return p;
}

// A pushed pile's contacts whose rounds fall into a two-round cycle (the same forces every other
// round, never settling) end as soon as the cycle shows, on the answer the stall would have ended
// on: one round less here, forty steps of a jam two rounds less each.
TEST(FrictionSolver, ATwoRoundCycleEndsAsSoonAsItShowsOnTheAnswerTheStallWouldEndOn) {
  const FrictionProblem p = read_problem(std::string(WYSIWYF_HAPTICS_DATA_DIR) + "/friction_two_round_cycle.txt");
  ASSERT_EQ(p.m.size(), 6u);
  const auto solve = [&](bool end_cycles) {
    FrictionSolver solver;
    solver.end_two_round_cycles = end_cycles;
    LcpSolver lcp;
    return solver.solve(lcp, p.m.at("A"), p.m.at("bn"), p.m.at("bt"), p.m.at("mu"), p.m.at("vt"), p.m.at("ft_start"),
                        p.clamped);
  };
  const FrictionResult stalled = solve(false), ended = solve(true);
  ASSERT_TRUE(stalled.ok && ended.ok);
  EXPECT_FALSE(stalled.converged || ended.converged);  // (a cycle: unsettled either way)
  EXPECT_EQ(stalled.iterations, 6);
  EXPECT_EQ(ended.iterations, 5);
  const double scale = stalled.fn.cwiseAbs().maxCoeff();
  EXPECT_LE((ended.fn - stalled.fn).cwiseAbs().maxCoeff(), 1e-8 * scale)
      << ended.fn.transpose() << " against " << stalled.fn.transpose();
  EXPECT_LE((ended.ft - stalled.ft).cwiseAbs().maxCoeff(), 1e-8 * scale)
      << ended.ft.transpose() << " against " << stalled.ft.transpose();
}

}  // namespace
}  // namespace wysiwyf::haptics
