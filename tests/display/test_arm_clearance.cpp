// ArmClearance on every arm the project ships (PUMA 560, UR5e, FR3): a part per collision box,
// cylinder and sphere of the URDF, named by link and shape; each part's distance to a point against
// a brute-force distance to points sampled on the shape's surface; its nearest point on the shape;
// its approach speed against finite differences of the nearest point along a joint motion; no
// allocation in evaluate; and a joint state of another joint count refused with both counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <set>
#include <string>

#include "arm_clearance/arm_clearance.hpp"
#include "arm_model/arm_model.hpp"
#include "wysiwyf/joint_positions.hpp"

// Every allocation of this test executable, counted: evaluate() must add none.
static std::atomic<long> g_allocations{0};
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// (GCC takes the replaced operator new for the standard one and warns of a mismatch with free.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace wysiwyf::robot {
namespace {

std::string urdf(const char* arm) { return std::string(WYSIWYF_CONFIG_DIR) + "/robots/" + arm + ".urdf"; }

// Joint values spread uniformly within the limits (continuous joints within +-pi).
JointVector random_q(const ArmModel& arm, std::mt19937_64& rng) {
  JointVector q(arm.dof());
  for (int j = 0; j < arm.dof(); ++j) {
    const double lo = std::max(arm.limits().lower[j], -M_PI), hi = std::min(arm.limits().upper[j], M_PI);
    q[j] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  return q;
}

// The supported collision shapes in the order of the parts.
std::vector<CollisionShape> supported_shapes(const ArmModel& arm) {
  std::vector<CollisionShape> shapes;
  for (const CollisionShape& s : arm.collision_shapes())
    if (s.supported()) shapes.push_back(s);
  return shapes;
}

// Points on the shape's surface (its own frame), about `step` m apart.
std::vector<Eigen::Vector3d> surface_samples(const CollisionShape& s, double step) {
  std::vector<Eigen::Vector3d> out;
  auto count = [&](double length) { return std::max(2, static_cast<int>(std::ceil(length / step)) + 1); };
  switch (s.type) {
    case ShapeType::kBox: {
      const Eigen::Vector3d h = 0.5 * s.box_size;
      for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const int nu = count(2 * h[u]), nv = count(2 * h[v]);
        for (int side = -1; side <= 1; side += 2)
          for (int i = 0; i < nu; ++i)
            for (int k = 0; k < nv; ++k) {
              Eigen::Vector3d p;
              p[axis] = side * h[axis];
              p[u] = -h[u] + 2 * h[u] * i / (nu - 1);
              p[v] = -h[v] + 2 * h[v] * k / (nv - 1);
              out.push_back(p);
            }
      }
      break;
    }
    case ShapeType::kCylinder: {
      const int around = count(2 * M_PI * s.radius), along = count(s.length), radial = count(s.radius);
      for (int a = 0; a < around; ++a) {
        const double phi = 2 * M_PI * a / around;
        const Eigen::Vector2d dir(std::cos(phi), std::sin(phi));
        for (int z = 0; z < along; ++z)
          out.emplace_back(s.radius * dir.x(), s.radius * dir.y(), -0.5 * s.length + s.length * z / (along - 1));
        for (int r = 0; r < radial; ++r)
          for (int side = -1; side <= 1; side += 2) {
            const double rho = s.radius * r / (radial - 1);
            out.emplace_back(rho * dir.x(), rho * dir.y(), side * 0.5 * s.length);
          }
      }
      break;
    }
    case ShapeType::kSphere: {
      const int rings = count(M_PI * s.radius);
      for (int i = 0; i <= rings; ++i) {
        const double theta = M_PI * i / rings;
        const int around = std::max(1, count(2 * M_PI * s.radius * std::sin(theta)));
        for (int a = 0; a < around; ++a) {
          const double phi = 2 * M_PI * a / around;
          out.push_back(s.radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                   std::cos(theta)));
        }
      }
      break;
    }
    case ShapeType::kMesh: break;
  }
  return out;
}

class ArmClearanceOn : public ::testing::TestWithParam<const char*> {};

TEST_P(ArmClearanceOn, HasAPartNamedByLinkAndShapeForEveryCollisionPrimitive) {
  const ArmModel arm(urdf(GetParam()), "dev");
  const ArmClearance clearance(arm);
  const auto shapes = supported_shapes(arm);
  ASSERT_EQ(clearance.parts(), shapes.size());
  std::set<std::string> names;
  for (std::size_t i = 0; i < clearance.parts(); ++i) {
    const std::string& name = clearance.part_name(i);
    EXPECT_EQ(name.rfind(shapes[i].link + " " + to_string(shapes[i].type), 0), 0u) << name;
    EXPECT_TRUE(names.insert(name).second) << "two parts called " << name;
  }
  // Every link on the chain with collision elements has parts (the arm, not only the device).
  for (int k = 0; k <= arm.dof(); ++k) {
    const std::string& link = arm.frame_name(arm.body_frame(k));
    const bool has_shapes = std::any_of(shapes.begin(), shapes.end(), [&](const auto& s) { return s.link == link; });
    const auto& without = arm.links_without_collision();
    if (std::find(without.begin(), without.end(), link) == without.end()) {
      EXPECT_TRUE(has_shapes) << link;
    }
  }
  for (const char* device : {"dev box", "knob cylinder", "ft_sensor cylinder", "marker_0 sphere"})
    EXPECT_EQ(names.count(device), 1u) << device;
}

// Each part's distance equals the distance to the nearest of points sampled 2 mm apart on its
// surface, to the sampling's resolution; its nearest point lies on the shape, that far from the point.
TEST_P(ArmClearanceOn, DistancesMatchABruteForceDistanceToTheShapesSurface) {
  const ArmModel arm(urdf(GetParam()), "dev");
  const ArmClearance clearance(arm);
  const auto shapes = supported_shapes(arm);
  std::vector<std::vector<Eigen::Vector3d>> samples;
  for (const auto& s : shapes) samples.push_back(surface_samples(s, 0.002));
  std::mt19937_64 rng(5);
  int outside = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const JointVector q = random_q(arm, rng), still = JointVector::Zero(arm.dof());
    const Eigen::Vector3d dev = arm.fk(q).translation();
    for (int k = 0; k < 4; ++k) {
      // Points around the plate, and anywhere in the arm's workspace.
      const Eigen::Vector3d point = k < 2 ? Eigen::Vector3d(dev + 0.15 * Eigen::Vector3d::Random())
                                          : Eigen::Vector3d(0.8 * Eigen::Vector3d::Random());
      const auto& parts = clearance.evaluate(q, still, point);
      for (std::size_t i = 0; i < shapes.size(); ++i) {
        const Eigen::Isometry3d base_T_shape = arm.fk(q, arm.frame(shapes[i].link)) * shapes[i].link_T_shape;
        const Eigen::Vector3d local = base_T_shape.inverse() * point;
        const double d = parts[i].distance;
        EXPECT_NEAR((point - parts[i].nearest).norm(), d, 1e-12) << parts[i].name;
        EXPECT_TRUE(shapes[i].contains(base_T_shape.inverse() * parts[i].nearest, 1e-9)) << parts[i].name;
        if (shapes[i].contains(local)) {
          EXPECT_EQ(d, 0.0) << parts[i].name << ": the point lies inside";
          continue;
        }
        ++outside;
        double brute = 1e9;
        for (const Eigen::Vector3d& s : samples[i]) brute = std::min(brute, (local - s).norm());
        EXPECT_LE(d, brute + 1e-9) << parts[i].name << " at " << point.transpose();
        EXPECT_GE(d, brute - 0.0015) << parts[i].name << " at " << point.transpose();
      }
    }
  }
  EXPECT_GT(outside, 100);
}

// The approach speed is the rate at which the nearest point closes on the point: along the
// direction to the point, the central difference of the nearest point as the joints move at qd.
TEST_P(ArmClearanceOn, ApproachSpeedsMatchFiniteDifferencesOfTheNearestPoint) {
  const ArmModel arm(urdf(GetParam()), "dev");
  const ArmClearance clearance(arm);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> rate(0.0, 0.5);
  const double h = 1e-6;
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const JointVector q = random_q(arm, rng);
    JointVector qd(arm.dof());
    for (int j = 0; j < arm.dof(); ++j) qd[j] = rate(rng);
    const Eigen::Vector3d point = arm.fk(q).translation() + 0.3 * Eigen::Vector3d::Random();
    const std::vector<PartClearance> now = clearance.evaluate(q, qd, point);
    const JointVector q_plus = q + h * qd, q_minus = q - h * qd;
    const std::vector<PartClearance> plus = clearance.evaluate(q_plus, qd, point);
    const std::vector<PartClearance> minus = clearance.evaluate(q_minus, qd, point);
    for (std::size_t i = 0; i < now.size(); ++i) {
      if (now[i].distance < 1e-3) continue;  // inside: no direction to the point
      const Eigen::Vector3d toward = (point - now[i].nearest) / now[i].distance;
      const double moved = toward.dot(plus[i].nearest - minus[i].nearest) / (2 * h);
      EXPECT_NEAR(now[i].approach_speed, moved, 1e-5 * (1 + std::abs(moved))) << now[i].name;
      EXPECT_NEAR(now[i].approach_speed, -(plus[i].distance - minus[i].distance) / (2 * h), 1e-5) << now[i].name;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST_P(ArmClearanceOn, EvaluateAllocatesNothing) {
  const ArmModel arm(urdf(GetParam()), "dev");
  const ArmClearance clearance(arm);
  std::mt19937_64 rng(3);
  const JointVector q = random_q(arm, rng), qd = JointVector::Constant(arm.dof(), 0.2);
  const Eigen::Vector3d point(0.7, 0.0, 0.1);
  clearance.evaluate(q, qd, point);
  const long before = g_allocations.load();
  double nearest = 1e9;
  for (int k = 0; k < 100; ++k)
    nearest = std::min(nearest, ArmClearance::nearest(clearance.evaluate(q, qd, point)).distance);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_LT(nearest, 1e9);
}

INSTANTIATE_TEST_SUITE_P(Arms, ArmClearanceOn, ::testing::Values("puma560", "ur5e", "fr3"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

// The PUMA's plate and knob as the device is built: the plate's front face is dev's z = 0, the
// knob's top 0.04 m in front of it; a point straight ahead of the knob is nearest the knob's top.
TEST(ArmClearance, ThePumasPlateAndKnobStandWhereTheDeviceIs) {
  const ArmModel arm(urdf("puma560"), "dev");
  const ArmClearance clearance(arm);
  const JointVector q = (JointVector(6) << 0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254).finished();
  const Eigen::Isometry3d base_T_dev = arm.fk(q);
  const Eigen::Vector3d ahead = base_T_dev * Eigen::Vector3d(0.0, 0.0, 0.1);
  const Eigen::Vector3d beside = base_T_dev * Eigen::Vector3d(0.06, 0.0, 0.03);
  const auto& parts = clearance.evaluate(q, JointVector::Zero(6), ahead);
  const PartClearance& nearest = ArmClearance::nearest(parts);
  EXPECT_STREQ(nearest.name, "knob cylinder");
  EXPECT_NEAR(nearest.distance, 0.06, 1e-9);
  EXPECT_LT((nearest.nearest - base_T_dev * Eigen::Vector3d(0.0, 0.0, 0.04)).norm(), 1e-9);
  for (const PartClearance& p : clearance.evaluate(q, JointVector::Zero(6), beside))
    if (std::string(p.name) == "dev box") {
      EXPECT_NEAR(p.distance, 0.03, 1e-9);
    }
}

TEST(ArmClearance, AJointStateOfAnotherJointCountIsRefusedWithBothCounts) {
  msg::JointState m;
  m.position().assign(6, 0.0);  // six positions
  JointVector q = JointVector::Zero(7);
  const std::string why = msgs::joint_positions(m, 7, q);
  EXPECT_NE(why.find("6 joint positions, expected 7"), std::string::npos) << why;
  EXPECT_EQ(q, JointVector::Zero(7)) << "a refused message leaves the joints as they were";
  EXPECT_EQ(msgs::joint_positions(m, 6, q), "");
  EXPECT_EQ(q.size(), 6);
  const ArmModel arm(urdf("fr3"), "dev");
  const ArmClearance clearance(arm);
  EXPECT_THROW(clearance.evaluate(JointVector::Zero(7), JointVector::Zero(6), Eigen::Vector3d::Zero()),
               std::invalid_argument);
}

}  // namespace
}  // namespace wysiwyf::robot
