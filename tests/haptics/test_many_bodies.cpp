// Many bodies against physical truths (issue 16): the scenes of config/scenes/ with a stack, a
// pile and a row of boxes, on simulated time. Penetration is measured independently of the
// simulation's own contacts: the separating-axis overlap of every pair of boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include "rigid_body/broad_phase.hpp"
#include "rigid_body/contact_islands.hpp"
#include "rigid_body/world.hpp"
#include "scene/scene.hpp"

namespace wysiwyf::haptics {

namespace {

Scene scene(const std::string& name) { return load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/scenes/" + name); }

WorldParams haptic_params(const Scene& s) {
  WorldParams p;
  p.gravity = s.gravity;
  p.rtol = kHapticRtol;  // as admittance_sim
  p.atol = kHapticRtol * 1e-2;
  return p;
}

// How deep two boxes overlap: the smallest overlap of their projections over the 15 separating
// axes (0 or less: apart). For boxes this is the depth a contact would have to push them apart.
double overlap(const World& w, int i, int j) {
  const BodyKinematics a = w.kinematics(i), b = w.kinematics(j);
  const Vec3 ha = w.model(i).half_extents, hb = w.model(j).half_extents;
  const Vec3 d = w.state(j).x - w.state(i).x;
  std::array<Vec3, 15> axes;
  int n = 0;
  for (int k = 0; k < 3; ++k) axes[n++] = a.R.col(k), axes[n++] = b.R.col(k);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      const Vec3 c = a.R.col(k).cross(b.R.col(l));
      if (c.norm() > 1e-6) axes[n++] = c.normalized();
    }
  double least = 1e300;
  for (int k = 0; k < n; ++k) {
    const Vec3& u = axes[k];
    double ra = 0, rb = 0;
    for (int l = 0; l < 3; ++l) ra += ha[l] * std::abs(u.dot(a.R.col(l))), rb += hb[l] * std::abs(u.dot(b.R.col(l)));
    least = std::min(least, ra + rb - std::abs(u.dot(d)));
  }
  return least;
}

double deepest_overlap(const World& w) {
  double deepest = 0;
  for (int i = 0; i < w.body_count(); ++i)
    for (int j = i + 1; j < w.body_count(); ++j)
      if (w.model(i).dynamic || w.model(j).dynamic) deepest = std::max(deepest, overlap(w, i, j));
  return deepest;
}

double kinetic_energy(const World& w) {
  double e = 0;
  for (int i = 0; i < w.body_count(); ++i) {
    if (!w.model(i).dynamic) continue;
    const BodyKinematics k = w.kinematics(i);
    e += 0.5 * w.model(i).mass * k.v.squaredNorm() + 0.5 * k.omega.dot(w.state(i).L);
  }
  return e;
}

// Steps a falling pile: the deepest overlap seen after any step, and the failures reported.
struct Landing {
  double transient = 0;
  int failures = 0, holds = 0;
};
Landing land(World& w, int steps) {
  Landing l;
  for (int step = 1; step <= steps; ++step) {
    const StepReport r = w.step(1e-3);
    l.failures += r.lcp_failures;
    l.holds += r.integration_failures;
    l.transient = std::max(l.transient, deepest_overlap(w));
  }
  return l;
}

}  // namespace

// Integrated throughout (sleeping off: the integration's own rest), and as admittance_sim runs it
// (the stack falls asleep once still and must still stand and carry its weight).
class StackOfFive : public ::testing::TestWithParam<double> {};

TEST_P(StackOfFive, StandsForAMinuteWithoutDriftOrPenetration) {
  const Scene s = scene("stack_5.yaml");
  WorldParams p = haptic_params(s);
  p.sleep_after = GetParam();
  World w(s.models, s.initial, p);
  const int table = s.body_index("table");
  double drift = 0, deepest = 0;
  int failures = 0;
  double weight_error = 0;
  const double weight = 5 * 0.5 * 9.81;
  for (int step = 1; step <= 60000; ++step) {
    const StepReport r = w.step(1e-3);
    failures += r.lcp_failures;
    if (step % 100 == 0) {
      deepest = std::max(deepest, deepest_overlap(w));
      for (int i = 0; i < w.body_count(); ++i) drift = std::max(drift, (w.state(i).x - s.initial[i].x).norm());
      // The total normal force under the stack (the table's contacts) is its weight.
      double under = 0;
      for (const auto& c : w.resting_contacts())
        if (c.feature.a == table || c.feature.b == table) under += c.force;
      weight_error = std::max(weight_error, std::abs(under - weight));
    }
  }
  RecordProperty("drift_um", std::to_string(drift * 1e6));
  RecordProperty("deepest_um", std::to_string(deepest * 1e6));
  std::printf("stack: drift %.3g um, deepest overlap %.3g um, weight error %.3g N, %d LCP failures\n", drift * 1e6,
              deepest * 1e6, weight_error, failures);
  EXPECT_LE(drift, 1e-4);
  EXPECT_LE(deepest, 1e-6);
  EXPECT_LE(weight_error, 1e-6 * weight);
  EXPECT_EQ(failures, 0);
  if (p.sleep_after > 0) {
    EXPECT_EQ(w.step(1e-3).bodies_asleep, 5) << "a stack still for a minute sleeps";
  }
}
INSTANTIATE_TEST_SUITE_P(ManyBodies, StackOfFive, ::testing::Values(0.0, WorldParams{}.sleep_after),
                         [](const auto& info) { return info.param > 0 ? "Sleeping" : "AlwaysIntegrated"; });

TEST(ManyBodies, APileOfSixteenBoxesComesToRestWithoutPenetration) {
  const Scene s = scene("pile_16.yaml");
  World w(s.models, s.initial, haptic_params(s));
  const auto [transient, failures, holds] = land(w, 3000);
  const double resting = deepest_overlap(w);
  std::printf("pile: at rest %.3g um deep, %.3g um at most while landing, kinetic energy %.3g J\n", resting * 1e6,
              transient * 1e6, kinetic_energy(w));
  EXPECT_LE(resting, 1e-5) << "at rest: no penetration beyond the contact tolerance";
  // While landing too (the 0.1 mm): features that do not yet face each other at a step's
  // start (a corner beside a face's rim, an edge pair beyond an end or just outside its cone) are
  // watched, so they cannot meet unseen within a step. Measured 0.8 um; 0.98-1.4 mm before.
  EXPECT_LE(transient, 1e-4);
  EXPECT_EQ(holds, 0);
  EXPECT_LE(kinetic_energy(w), 1e-9) << "at rest";
  EXPECT_EQ(failures, 0);
  for (int i = 0; i < w.body_count(); ++i)
    if (w.model(i).dynamic) {
      EXPECT_GT(w.state(i).x.z(), 0) << w.model(i).name << " fell off the table";
    }
}

// The same pile dropped from perturbed poses (each box moved up to 5 mm and turned up to 0.2 rad at
// random): no landing may pass a box into another deeper than 0.1 mm, whatever path it takes.
// With corners beside a rim watched but not edge pairs beyond an end, and a watched cone of 0.05,
// piles 2 and 4 went 1.7 mm and 0.17 mm deep. Pile 41: an edge pair whose normal turned 0.3 rad
// in a step, from outside the watched cone to 0.1 mm deep, before such pairs were watched too.
TEST(ManyBodies, RandomPilesLandWithoutPassingABoxIntoAnother) {
  const Scene s = scene("pile_16.yaml");
  std::vector<int> seeds;
  for (int seed = 1; seed <= 20; ++seed) seeds.push_back(seed);
  seeds.push_back(41);
  for (const int seed : seeds) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<BodyState> initial = s.initial;
    for (std::size_t i = 0; i < initial.size(); ++i) {
      if (!s.models[i].dynamic) continue;
      initial[i].x += 0.005 * Vec3(u(rng), u(rng), u(rng));
      const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
      initial[i].q = (initial[i].q * Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * u(rng), axis))).normalized();
    }
    World w(s.models, initial, haptic_params(s));
    const auto [transient, failures, holds] = land(w, 1500);
    std::printf("random pile %d: %.3g um at most while landing\n", seed, transient * 1e6);
    EXPECT_LE(transient, 1e-4) << "pile " << seed;
    EXPECT_EQ(holds, 0) << "pile " << seed;
    EXPECT_EQ(failures, 0) << "pile " << seed;
  }
}

// A box slid over the table's edge, turned to it, tips off over the edge: flat on the table, its
// bottom face rests on the table's edge where the face's own edges cross it (edge-edge contacts
// whose normal is the face's; a tilt of round-off put the face, not its edge, at the support and
// dropped them). Before they were kept, the box turned 0.7 rad went 0.56 mm into the table's edge,
// and piles' boxes that slid to the edge sank as deep (random piles 14 and 20 above: 0.11, 0.37 mm).
TEST(ManyBodies, ABoxSlidOverTheTablesEdgeTipsOffWithoutSinkingIntoIt) {
  for (const double yaw : {0.3, 0.7}) {
    BodyModel box;
    box.name = "box";
    box.half_extents = Vec3(0.05, 0.04, 0.03);
    box.mass = 0.2;
    box.inertia_body = BodyModel::box_inertia(box.mass, box.half_extents);
    box.friction = 0.4;
    BodyModel table;
    table.name = "table";
    table.dynamic = false;
    table.half_extents = Vec3(0.3, 0.3, 0.025);
    table.friction = 0.4;
    BodyState b, t;
    b.x = Vec3(0.27, 0, 0.03);
    b.q = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()));
    b.P = box.mass * Vec3(0.6, 0, 0);
    t.x = Vec3(0, 0, -0.025);
    WorldParams p;
    p.rtol = kHapticRtol;
    p.atol = kHapticRtol * 1e-2;
    World w({box, table}, {b, t}, p);
    double deepest = 0;
    int failures = 0;
    for (int step = 1; step <= 400 && w.state(0).x.z() > -0.05; ++step) {
      const StepReport r = w.step(1e-3);
      failures += r.lcp_failures + r.integration_failures;
      deepest = std::max(deepest, overlap(w, 0, 1));
    }
    std::printf("box over the edge, turned %.1f rad: %.3g um deep at most, fell to z = %.3f m\n", yaw, deepest * 1e6,
                w.state(0).x.z());
    EXPECT_LE(deepest, 1e-5) << "turned " << yaw;
    EXPECT_EQ(failures, 0);
    EXPECT_LT(w.state(0).x.z(), 0) << "it tipped off the table";
  }
}

// Newton's cradle in a row: box 1 slides at 0.5 m/s into box 2 (frictionless table, e = 0.9 between
// the boxes), which hits box 3, and so on. No horizontal force acts but between boxes: the row's
// momentum stays; each impact between equal masses leaves the pair (1 -/+ e) / 2 of the closing
// speed; kinetic energy only falls.
TEST(ManyBodies, PushingARowOfThirtyTwoBoxesConservesMomentumThroughItsImpacts) {
  const Scene s = scene("row_32.yaml");
  World w(s.models, s.initial, haptic_params(s));
  const double v0 = 0.5, m = 0.05, e = 0.9;
  BodyState first = w.state(1);
  first.P = Vec3(m * v0, 0, 0);
  w.set_state(1, first);
  auto momentum = [&] {
    double p = 0;
    for (int i = 1; i < w.body_count(); ++i) p += w.state(i).P.x();
    return p;
  };
  double worst = 0, energy = kinetic_energy(w), rise = 0;
  bool first_impact_checked = false;
  int failures = 0;
  for (int step = 1; step <= 2500; ++step) {
    const StepReport r = w.step(1e-3);
    failures += r.lcp_failures;
    worst = std::max(worst, std::abs(momentum() - m * v0));
    const double now = kinetic_energy(w);
    rise = std::max(rise, now - energy);
    energy = now;
    if (!first_impact_checked && w.kinematics(2).v.x() > 0) {
      // box 1 had 1 cm to travel at 0.5 m/s: the first impact is inside the 20th step
      EXPECT_NEAR(w.kinematics(1).v.x(), (1 - e) / 2 * v0, 1e-6);
      EXPECT_NEAR(w.kinematics(2).v.x(), (1 + e) / 2 * v0, 1e-6);
      first_impact_checked = true;
    }
  }
  std::printf("row: momentum off by %.3g of %.3g, kinetic energy rose by %.3g J at most, last box at %.3g m/s\n", worst,
              m * v0, rise, w.kinematics(32).v.x());
  EXPECT_TRUE(first_impact_checked);
  EXPECT_LE(worst, 1e-9 * m * v0);
  EXPECT_LE(rise, 1e-12);
  // Each impact of the row is a pair's alone (the boxes behind fall back): the last box leaves
  // with ((1 + e) / 2)^31 of the first one's speed.
  EXPECT_NEAR(w.kinematics(32).v.x(), v0 * std::pow((1 + e) / 2, 31), 1e-6) << "the impacts reach the end of the row";
  EXPECT_EQ(failures, 0);
}

// The sweep finds exactly the pairs whose grown boxes overlap (every pair tested), however the
// bodies move between calls (its kept order goes stale), static pairs never.
// The warm start of an island follows its contacts: when contacts come and go (a box pushed
// through a pile), each contact clamped before is clamped in its new island's warm start, at its
// new place, and one that no longer touches drops out; each contact's friction goes with it.
TEST(IslandGrouping, AWarmStartFollowsItsContactsWhenTheIslandChanges) {
  // Bodies 0 (the table, static), 1, 2, 3 (dynamic); contacts named by (a, b, vertex of a).
  const std::vector<int> slot = {-1, 0, 1, 2};
  auto contact = [](int a, int b, int vertex) {
    ActiveContact c;
    c.feature.a = a, c.feature.b = b, c.feature.feature_a = vertex, c.feature.feature_b = 5;
    return c;
  };
  IslandGrouping grouping;
  std::vector<ActiveContact> before = {contact(1, 0, 0), contact(1, 0, 1), contact(2, 1, 0), contact(2, 1, 3),
                                       contact(3, 0, 2)};
  std::vector<ContactIsland> islands;
  grouping.group(before, slot, islands, {});
  ASSERT_EQ(islands.size(), 2u);  // boxes 1 and 2 together, box 3 alone
  ASSERT_EQ(islands[0].end - islands[0].begin, 4u);
  islands[0].clamped = LcpIndices{{3, 0}};  // (2, 1, 3) and (1, 0, 0)
  islands[1].clamped = LcpIndices{{0}};     // (3, 0, 2)
  for (std::size_t i = 0; i < before.size(); ++i) before[i].friction = Vec3(0.1 * static_cast<double>(i + 1), 0, 0);
  // (1, 0, 0) lifts off, a new corner of box 2 lands on box 1, box 3 touches box 2 (one island now).
  std::vector<ActiveContact> after = {contact(1, 0, 1), contact(2, 1, 0), contact(2, 1, 3),
                                      contact(2, 1, 6), contact(3, 0, 2), contact(3, 2, 4)};
  grouping.group(after, slot, islands, before);
  ASSERT_EQ(islands.size(), 1u);
  std::vector<ContactFeature> warm;
  for (const int i : islands[0].clamped) warm.push_back(after[islands[0].begin + static_cast<std::size_t>(i)].feature);
  ASSERT_EQ(warm.size(), 2u);
  EXPECT_TRUE(warm[0] == contact(2, 1, 3).feature);
  EXPECT_TRUE(warm[1] == contact(3, 0, 2).feature);
  // And so does each contact's friction (a new contact has none).
  for (const ActiveContact& c : after) {
    const auto was =
        std::find_if(before.begin(), before.end(), [&](const ActiveContact& b) { return b.feature == c.feature; });
    EXPECT_EQ(c.friction, was == before.end() ? Vec3::Zero() : was->friction);
  }
  // The same contacts again: the warm start stays as it is.
  const LcpIndices kept = islands[0].clamped;
  const std::vector<ActiveContact> again = after;
  grouping.group(after, slot, islands, again);
  EXPECT_EQ(islands[0].clamped, kept);
}

TEST(BroadPhase, SweepAndPruneFindsThePairsThatTestingEveryPairFinds) {
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> unit(-1, 1), size(0.02, 0.3);
  std::vector<BodyModel> bodies(40);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].half_extents = Vec3(size(rng), size(rng), size(rng));
    bodies[i].dynamic = i % 8 != 0;  // some static: a table and walls
  }
  const WorldModel model(bodies, WorldParams{});
  std::vector<Pose> poses(bodies.size());
  SweepAndPrune sweep;
  std::vector<BodyPair> found, expected;
  std::size_t total = 0;
  for (int round = 0; round < 50; ++round) {
    const double spread = round < 25 ? 1.0 : 0.3;  // then crowded: many overlaps
    for (auto& p : poses) {
      p.x = spread * Vec3(unit(rng), unit(rng), unit(rng));
      p.R = Eigen::AngleAxisd(3 * unit(rng), Vec3(unit(rng), unit(rng), unit(rng)).normalized()).toRotationMatrix();
    }
    sweep.pairs(model, poses, 0.01, found);
    all_pairs(model, poses, 0.01, expected);
    ASSERT_EQ(found, expected) << "round " << round;
    total += found.size();
  }
  EXPECT_GT(total, 500u) << "the rounds test overlapping pairs";
}

namespace {

// 10 cm, 1 kg cubes at `centres` on a large table, all with friction mu.
World cubes_on_table(const std::vector<Vec3>& centres, double mu, const WorldParams& p) {
  std::vector<BodyModel> models;
  std::vector<BodyState> states;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    BodyModel cube;
    cube.name = "cube" + std::to_string(i);
    cube.half_extents = Vec3::Constant(0.05);
    cube.mass = 1;
    cube.inertia_body = BodyModel::box_inertia(1, cube.half_extents);
    cube.friction = mu;
    models.push_back(cube);
    BodyState s;
    s.x = centres[i];
    states.push_back(s);
  }
  BodyModel table;
  table.name = "table";
  table.dynamic = false;
  table.half_extents = Vec3(50, 50, 0.05);
  table.friction = mu;
  models.push_back(table);
  BodyState t;
  t.x = Vec3(0, 0, -0.05);
  states.push_back(t);
  return World(models, states, p);
}

// n cubes in a row along x, `gap` apart, at the haptic tolerances.
World cube_row(int n, double gap, double mu) {
  std::vector<Vec3> centres;
  for (int i = 0; i < n; ++i) centres.emplace_back((0.1 + gap) * i, 0, 0.05);
  WorldParams p;
  p.rtol = kHapticRtol;
  p.atol = kHapticRtol * 1e-2;
  return cubes_on_table(centres, mu, p);
}

}  // namespace

// The hand drives the first cube of a frictionless row back and forth (a stiff velocity servo,
// up to 20 N, as the admittance display's user at up to 0.75 m/s, with sensor noise) into the
// others. Equal boxes side by side put corners on the rims of each other's faces and make the
// contact LCP degenerate; before this held, the row stopped the integrator within a second
// (CV_TOO_MUCH_WORK at t = 0.99 s, the pivoting cycling on a face pressed from both sides).
TEST(ManyBodies, AFrictionlessRowPushedBackAndForthStaysApartWithoutFailures) {
  World w = cube_row(5, 0.05, 0);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0, 0.05);
  double deepest = 0, lowest = 1;
  int lcp_failures = 0, integration_failures = 0, collisions = 0;
  for (int k = 0; k < 10000; ++k) {  // 10 s
    const double t = k * 1e-3;
    const double v = 0.5 * std::sin(M_PI * t) + 0.25;  // the hand's speed
    const Vec3 push(std::clamp(50 * (v - w.kinematics(0).v.x()), -20.0, 20.0), 0, 0);
    w.set_external_wrench(0, push + Vec3(noise(rng), noise(rng), noise(rng)), Vec3::Zero());
    const StepReport r = w.step(1e-3);
    lcp_failures += r.lcp_failures;
    integration_failures += r.integration_failures;
    collisions += r.collisions;
    deepest = std::max(deepest, deepest_overlap(w));
    for (int i = 0; i < 5; ++i) lowest = std::min(lowest, w.state(i).x.z());
  }
  EXPECT_EQ(integration_failures, 0) << w.last_failure();
  EXPECT_EQ(lcp_failures, 0);
  EXPECT_GT(collisions, 4) << "the pushed cube reaches the others";
  EXPECT_GT(w.state(4).x.x(), 0.5) << "the last cube was pushed along";
  EXPECT_LT(deepest, 1e-6) << "m, the deepest overlap of two boxes";
  EXPECT_GT(lowest, 0.05 - 1e-6) << "m, the lowest centre (the table is at 0)";
}

// The second object of the display (two_objects.yaml): the user pushes the box (7 N, as through
// the plate) along the wooden table into the cube 6 cm away, and on until the cube stands at the
// far wall. A 12 cm face on a 20 cm one, their top and bottom edges level: the corners of the box
// lie on the rims of the cube's face. Before settle_speed, the box caught up with the sliding cube
// at 8.8 mm/s, too slow for an impact; the gap feedback let it 26 um in, past the rim, where its
// corners went over to the cube's top and bottom faces, and it passed through the cube.
TEST(ManyBodies, ABoxPushedIntoTheCubeDrivesItToTheWallWithoutPassingIntoIt) {
  const Scene s = scene("two_objects.yaml");
  World w(s.models, s.initial, haptic_params(s));
  const int box = s.body_index("box"), cube = s.body_index("cube");
  ASSERT_GE(box, 0);
  ASSERT_GE(cube, 0);
  const double e = 0.3;  // both boxes' restitution; equal masses (1 kg)
  w.set_external_wrench(box, Vec3(0, 7, 0), Vec3::Zero());
  double deepest = 0, box_before = 0;
  int failures = 0, holds = 0;
  bool impact_checked = false;
  for (int step = 1; step <= 1500; ++step) {
    const StepReport r = w.step(1e-3);
    failures += r.lcp_failures;
    holds += r.integration_failures;
    deepest = std::max(deepest, deepest_overlap(w));
    const double v_box = w.kinematics(box).v.y(), v_cube = w.kinematics(cube).v.y();
    if (!impact_checked && v_cube > 1e-6) {  // (the resting cube's round-off, 1e-14 m/s, is no impact)
      // The impact of the restitution law; the table's friction (2.94 N on each) and the push act
      // over the rest of the step (at most 7 mm/s).
      EXPECT_NEAR(v_box, (1 - e) / 2 * box_before, 7e-3);
      EXPECT_NEAR(v_cube, (1 + e) / 2 * box_before, 7e-3);
      EXPECT_GT(box_before, 0.6) << "m/s, the box's speed when it struck (4.06 m/s^2 over 6 cm: 0.70)";
      impact_checked = true;
    }
    box_before = v_box;
  }
  std::printf("two objects: deepest overlap %.3g um; cube at y = %.6f, box at %.6f\n", deepest * 1e6,
              w.state(cube).x.y(), w.state(box).x.y());
  EXPECT_TRUE(impact_checked);
  EXPECT_LT(deepest, 1e-6) << "m, the deepest overlap of two boxes";
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(holds, 0) << w.last_failure();
  EXPECT_NEAR(w.state(cube).x.y(), 0.15, 1e-6) << "the cube at the far wall";
  EXPECT_NEAR(w.state(box).x.y(), 0.15 - 0.16, 1e-6) << "the box against the cube";
  EXPECT_LT(kinetic_energy(w), 1e-9);
}

// A step that cannot be integrated neither throws nor moves anything: 25 cubes stacked are one
// island of 196 contacts, beyond the LCP's 96, so the contact forces cannot be found.
TEST(ManyBodies, AStepThatCannotBeIntegratedHoldsTheBodiesWhereTheyWere) {
  const int n = 25;
  std::vector<Vec3> centres;
  for (int i = 0; i < n; ++i) centres.emplace_back(0, 0, 0.05 + 0.1 * i);
  World w = cubes_on_table(centres, 0, WorldParams{});
  w.set_external_wrench(n - 1, Vec3(3, 0, 0), Vec3::Zero());
  for (int k = 0; k < 3; ++k) {
    StepReport r;
    ASSERT_NO_THROW(r = w.step(1e-3));
    EXPECT_EQ(r.integration_failures, 1);
    EXPECT_EQ(r.frictionless_retries, 1);
    EXPECT_NEAR(w.time(), (k + 1) * 1e-3, 1e-15);
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(w.state(i).x, centres[i]) << "cube " << i;
      EXPECT_EQ(w.state(i).P, Vec3::Zero()) << "cube " << i;
    }
  }
  EXPECT_NE(w.last_failure().find("96"), std::string::npos) << w.last_failure();
}

}  // namespace wysiwyf::haptics
