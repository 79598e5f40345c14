// The surface planner's choice of feature (components/display/surface_planner/feature_choice),
// against the stated truth: the displayable feature nearest the hand's predicted path, the path
// being the hand's motion extrapolated over the horizon and ending where the hand would stop
// (entering an object, or on the knob). The truth is computed here by brute force: the path
// clipped where it enters a box or the sphere about the knob tip, and sampled every 0.2 mm (the
// chooser samples it at 97 points).
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "../../components/display/surface_planner/feature_choice.hpp"
#include "scene/scene.hpp"

namespace wysiwyf::display {

namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kHorizon = 0.8, kHysteresis = 0.03, kDwell = 0.1;

struct World {
  haptics::Scene scene = haptics::load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/scenes/display_demo.yaml");
  std::vector<Eigen::Isometry3d> base_T_obj;
  World() {
    for (const auto& s : scene.initial) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = s.q.toRotationMatrix();
      T.translation() = s.x;
      base_T_obj.push_back(T);
    }
  }
  const haptics::DisplayFeature& feature(const std::string& name) const { return *scene.feature(name); }
};

// Where along p + t d (t in [0, t_max]) the ray first enters an axis-aligned box (body frame) or a
// sphere; t_max if it does not.
double box_entry(const Vec3& p, const Vec3& d, const Vec3& half, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(p[i]) >= half[i]) return t_max;
      continue;
    }
    double a = (-half[i] - p[i]) / d[i], b = (half[i] - p[i]) / d[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  return t0 <= t1 ? t0 : t_max;
}

double sphere_entry(const Vec3& p, const Vec3& d, const Vec3& centre, double radius, double t_max) {
  const Vec3 m = p - centre;
  const double a = d.squaredNorm(), b = m.dot(d), c = m.squaredNorm() - radius * radius;
  const double disc = b * b - a * c;
  if (disc < 0) return t_max;
  const double t = (-b - std::sqrt(disc)) / a;
  return t >= 0 && t < t_max ? t : t_max;
}

// The stated truth: each feature's distance to the clipped path.
std::vector<double> truth(const World& w, const Vec3& hand, const Vec3& velocity) {
  double t_end = kHorizon;
  for (std::size_t i = 0; i < w.scene.models.size(); ++i) {
    const Eigen::Isometry3d obj_T_base = w.base_T_obj[i].inverse();
    t_end = std::min(
        t_end, box_entry(obj_T_base * hand, obj_T_base.linear() * velocity, w.scene.models[i].half_extents, kHorizon));
  }
  for (const auto& f : w.scene.features)
    if (f.kind == haptics::DisplayFeature::Kind::kKnob)
      t_end = std::min(t_end, sphere_entry(hand, velocity, w.base_T_obj[f.body] * f.touch, f.knob_radius, kHorizon));
  const int n = std::max(1, static_cast<int>(velocity.norm() * t_end / 2e-4));
  std::vector<double> distance;
  for (const auto& f : w.scene.features) {
    const Eigen::Isometry3d obj_T_base = w.base_T_obj[static_cast<std::size_t>(f.body)].inverse();
    const Vec3& half = w.scene.models[static_cast<std::size_t>(f.body)].half_extents;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= n; ++k) {
      const Vec3 local = obj_T_base * (hand + velocity * (t_end * k / n));
      if (f.in_front(local)) best = std::min(best, f.distance(local) + f.past_edges(local, half));
    }
    distance.push_back(best);
  }
  return distance;
}

const haptics::DisplayFeature* first_choice(const World& w, const Vec3& hand, const Vec3& velocity) {
  FeatureChooser chooser(kHorizon, kHysteresis, kDwell);
  return chooser.choose(w.scene, w.base_T_obj, hand, velocity, 0);
}

}  // namespace

// A hand at rest beyond the edge between two faces is as near one as the other by distance (both
// nearest points on the edge); it belongs to the face whose plane it is farther out of. The
// stereo demo's user waits there between contacts, 40 cm out of the -y face's plane and on the
// +x face's, and the keyed hand's centre is 10 cm behind the fingertip, toward +x.
TEST(FeatureChoice, AHandBeyondAnEdgeBelongsToTheFaceItIsFartherOutOf) {
  const World w;
  const Vec3 cube = w.base_T_obj[static_cast<std::size_t>(w.scene.body_index("cube"))].translation();
  const Vec3 half = w.scene.models[static_cast<std::size_t>(w.scene.body_index("cube"))].half_extents;
  const double h = half.x();
  const auto& plus_x = w.feature("cube +x face");
  const auto& minus_y = w.feature("cube -y face");
  for (const double out : {0.0, 0.05, 0.095, 0.2, 0.39}) {
    const Vec3 local(h + out, -h - 0.4, 0);
    EXPECT_NEAR(plus_x.distance(local), minus_y.distance(local), 1e-9);
    EXPECT_NEAR(minus_y.past_edges(local, half), 0.0, 1e-12);
    EXPECT_NEAR(plus_x.past_edges(local, half), 0.4 - out, 1e-12);
    EXPECT_EQ(first_choice(w, cube + local, Vec3::Zero())->name, "cube -y face") << out << " m out of +x's plane";
  }
  // Past the bisector, a feature of the +x face's.
  EXPECT_EQ(first_choice(w, cube + Vec3(h + 0.41, -h - 0.4, 0), Vec3::Zero())->name, "cube +x face");
  // Straight in front of a face, nothing is added.
  EXPECT_NEAR(plus_x.past_edges(Vec3(h + 0.3, 0.02, -0.01), half), 0.0, 1e-12);
}

TEST(FeatureChoice, AReachStraightAtAFeatureChoosesIt) {
  const World w;
  // At the knob, from in front; at the side faces, from the sides.
  EXPECT_EQ(first_choice(w, {1.1, 0.0, 0.1}, {-1.0, 0, 0})->name, "cube +x knob");
  EXPECT_EQ(first_choice(w, {0.6, 0.5, 0.12}, {0, -1.2, 0})->name, "cube +y face");
  EXPECT_EQ(first_choice(w, {0.55, -0.6, 0.05}, {0, 1.0, 0})->name, "cube -y face");
  // Beside the knob, into the +x face: the face (the path passes the knob 5 cm off).
  EXPECT_EQ(first_choice(w, {1.1, 0.05, 0.15}, {-1.0, 0, 0})->name, "cube +x face");
  // Down onto the top.
  EXPECT_EQ(first_choice(w, {0.6, 0.0, 0.5}, {0, 0, -1.0})->name, "cube +z face");
}

// Random reaches from around the cube at random points of its visible faces: the chosen feature
// is one nearest the predicted path (within 1 mm of the nearest: the path is sampled).
TEST(FeatureChoice, TheChosenFeatureIsTheOneNearestThePredictedPath) {
  const World w;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), speed(0.2, 1.6);
  const Vec3 centre = w.base_T_obj[static_cast<std::size_t>(w.scene.body_index("cube"))].translation();
  int checked = 0, stopped_short = 0;
  for (int i = 0; i < 400; ++i) {
    // A start 25 to 60 cm from the cube's centre, on the side away from the wall, above the table.
    Vec3 dir(std::abs(unit(rng)) + 0.2, unit(rng), std::abs(unit(rng)));
    dir.normalize();
    const Vec3 hand = centre + dir * (0.25 + 0.35 * std::abs(unit(rng)));
    const Vec3 aim = centre + Vec3(0.1, 0.1 * unit(rng), 0.1 * unit(rng)) * (i % 2 ? 1.0 : 0.0) +
                     Vec3(0.1 * unit(rng), 0.1 * unit(rng), 0.1) * (i % 2 ? 0.0 : 1.0);
    const Vec3 velocity = (aim - hand).normalized() * speed(rng);
    const auto distance = truth(w, hand, velocity);
    const double nearest = *std::min_element(distance.begin(), distance.end());
    const haptics::DisplayFeature* chosen = first_choice(w, hand, velocity);
    ASSERT_NE(chosen, nullptr);
    const auto index = static_cast<std::size_t>(chosen - w.scene.features.data());
    EXPECT_LE(distance[index], nearest + 1e-3)
        << "a hand at " << hand.transpose() << " moving at " << velocity.transpose() << ": chose '" << chosen->name
        << "' " << distance[index] * 1e3 << " mm from its path, the nearest is " << nearest * 1e3 << " mm";
    ++checked;
    stopped_short += nearest > 0.05;
  }
  EXPECT_EQ(checked, 400);
  EXPECT_LT(stopped_short, 200);  // most reaches get to the cube within the horizon
}

// A path passing nearly as near another feature does not take the target from the current one;
// one nearer by the hysteresis takes it after the dwell, not before.
TEST(FeatureChoice, HysteresisAndDwellKeepTheTargetFromFlipping) {
  const World w;
  FeatureChooser chooser(kHorizon, kHysteresis, kDwell);
  auto choose = [&](const Vec3& hand, const Vec3& aim, std::int64_t t_ns) {
    return chooser.choose(w.scene, w.base_T_obj, hand, (aim - hand).normalized(), t_ns)->name;
  };
  // Toward the cube's +x+y edge from in front and to the side: into the +x face 1 cm from the edge.
  const Vec3 hand(0.95, 0.35, 0.1);
  EXPECT_EQ(choose(hand, {0.70, 0.09, 0.1}, 0), "cube +x face");
  // Then into the +y face 1 cm from the edge, for 0.5 s: the +y face is nearer, by 1 cm, not 3.
  for (std::int64_t t = 1; t <= 500; ++t) ASSERT_EQ(choose(hand, {0.69, 0.10, 0.1}, t * 1'000'000), "cube +x face");
  // From the side, at the +y face's middle: the +x face is not in the path's view at all. Taken
  // after 0.1 s, not before.
  const Vec3 side(0.6, 0.45, 0.1);
  const std::int64_t t0 = 600'000'000;
  for (std::int64_t t = t0; t < t0 + 100'000'000; t += 1'000'000)
    ASSERT_EQ(choose(side, {0.6, 0.1, 0.1}, t), "cube +x face") << (t - t0) * 1e-6 << " ms";
  EXPECT_EQ(choose(side, {0.6, 0.1, 0.1}, t0 + 100'000'000), "cube +y face");
}

}  // namespace wysiwyf::display
