// ArmModel's collision shapes: the primitives' point test, the device's shapes below the flange
// alike on every arm, meshes reported and not loaded, the PUMA URDF's link capsules, and
// the UR5e's and FR3's primitives covering each link's kinematic skeleton and centre of mass.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "arm_model_test_util.hpp"

namespace wysiwyf::robot {
namespace {

using test::kFr3Urdf;
using test::kPumaUrdf;
using test::kUr5eUrdf;

TEST(ArmModelCollision, PrimitivesContainTheirInsideOnly) {
  CollisionShape box;
  box.type = ShapeType::kBox;
  box.box_size = Eigen::Vector3d(0.2, 0.4, 0.6);
  EXPECT_TRUE(box.contains(Eigen::Vector3d(0.099, -0.199, 0.299)));
  EXPECT_FALSE(box.contains(Eigen::Vector3d(0.101, 0.0, 0.0)));
  EXPECT_TRUE(box.contains(Eigen::Vector3d(0.101, 0.0, 0.0), 0.002));
  CollisionShape cylinder;
  cylinder.type = ShapeType::kCylinder;
  cylinder.radius = 0.1;
  cylinder.length = 0.4;
  EXPECT_TRUE(cylinder.contains(Eigen::Vector3d(0.07, 0.07, 0.19)));
  EXPECT_FALSE(cylinder.contains(Eigen::Vector3d(0.08, 0.08, 0.0)));
  EXPECT_FALSE(cylinder.contains(Eigen::Vector3d(0.0, 0.0, 0.21)));
  CollisionShape sphere;
  sphere.type = ShapeType::kSphere;
  sphere.radius = 0.1;
  EXPECT_TRUE(sphere.contains(Eigen::Vector3d(0.05, 0.05, 0.05)));
  EXPECT_FALSE(sphere.contains(Eigen::Vector3d(0.06, 0.06, 0.06)));
  CollisionShape mesh;
  mesh.type = ShapeType::kMesh;
  EXPECT_FALSE(mesh.supported());
  EXPECT_FALSE(mesh.contains(Eigen::Vector3d::Zero()));
}

// The device below the flange (sensor, plate, knob) has the same shapes on every arm, posed
// alike relative to the flange.
TEST(ArmModelCollision, TheDeviceHasTheSameShapesOnEveryArm) {
  const ArmModel puma(kPumaUrdf), ur5e(kUr5eUrdf), fr3(kFr3Urdf);
  auto device = [](const ArmModel& arm) {
    std::vector<std::pair<std::string, Eigen::Isometry3d>> shapes;
    const Eigen::Isometry3d flange_T_body = arm.body_T_frame(arm.frame("flange")).inverse();
    for (const CollisionShape& s : arm.collision_shapes())
      if (s.link == "ft_sensor" || s.link == "dev" || s.link == "knob")
        shapes.emplace_back(s.link, flange_T_body * s.body_T_shape);
    return shapes;
  };
  const auto reference = device(puma);
  ASSERT_EQ(reference.size(), 3u);
  for (const ArmModel* arm : {&ur5e, &fr3}) {
    const auto shapes = device(*arm);
    ASSERT_EQ(shapes.size(), reference.size()) << arm->urdf_path();
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      EXPECT_EQ(shapes[i].first, reference[i].first);
      EXPECT_LT((shapes[i].second.matrix() - reference[i].second.matrix()).cwiseAbs().maxCoeff(), 1e-12);
    }
    for (const char* name : {"ft_sensor", "dev", "marker_0", "marker_1", "marker_2", "marker_3", "knob"}) {
      const Eigen::Isometry3d here =
          arm->body_T_frame(arm->frame("flange")).inverse() * arm->body_T_frame(arm->frame(name));
      const Eigen::Isometry3d there =
          puma.body_T_frame(puma.frame("flange")).inverse() * puma.body_T_frame(puma.frame(name));
      EXPECT_TRUE(here.isApprox(there, 1e-12)) << arm->urdf_path() << " " << name;
    }
  }
}

// config/robots/puma560.urdf gives each arm link a capsule (a cylinder and a sphere of its radius
// at each end) along the segment between the link's joint origins (the pedestal from 0.6 m below
// the base up to it); link5 (zero length between the wrist axes) and the flange carry none.
TEST(ArmModelCollision, ThePumaUrdfsArmLinksAreCapsulesBetweenTheirJointOrigins) {
  const ArmModel arm(kPumaUrdf);
  const JointVector q0 = JointVector::Zero(arm.dof());
  struct Capsule {
    const char* link;
    double radius;
    Eigen::Vector3d from, to;  // in the link's frame
  };
  auto in_link = [&](const char* link, const char* other) {
    return (arm.fk(q0, arm.frame(link)).inverse() * arm.fk(q0, arm.frame(other))).translation();
  };
  const Capsule expected[] = {
      {"base_link", 0.09, Eigen::Vector3d(0, 0, -0.6), Eigen::Vector3d::Zero()},
      {"link1", 0.09, Eigen::Vector3d::Zero(), in_link("link1", "link2")},
      {"link2", 0.07, Eigen::Vector3d::Zero(), in_link("link2", "link3")},
      {"link3", 0.055, Eigen::Vector3d::Zero(), in_link("link3", "link4")},
      {"link4", 0.04, Eigen::Vector3d::Zero(), in_link("link4", "link5")},
      {"link6", 0.04, Eigen::Vector3d::Zero(), in_link("link6", "flange")},
  };
  for (const Capsule& c : expected) {
    std::vector<const CollisionShape*> cylinders, spheres;
    for (const CollisionShape& s : arm.collision_shapes()) {
      if (s.link != c.link) continue;
      (s.type == ShapeType::kCylinder ? cylinders : spheres).push_back(&s);
      EXPECT_NE(s.type, ShapeType::kBox) << c.link;
      EXPECT_NEAR(s.radius, c.radius, 1e-12) << c.link;
    }
    ASSERT_EQ(cylinders.size(), 1u) << c.link;
    ASSERT_EQ(spheres.size(), 2u) << c.link;
    const CollisionShape& cylinder = *cylinders[0];
    const Eigen::Vector3d end_a = cylinder.link_T_shape * Eigen::Vector3d(0, 0, -0.5 * cylinder.length);
    const Eigen::Vector3d end_b = cylinder.link_T_shape * Eigen::Vector3d(0, 0, 0.5 * cylinder.length);
    const bool forward = (end_a - c.from).norm() < (end_b - c.from).norm();
    EXPECT_LT(((forward ? end_a : end_b) - c.from).norm(), 1e-9) << c.link;
    EXPECT_LT(((forward ? end_b : end_a) - c.to).norm(), 1e-9) << c.link;
    EXPECT_LT((spheres[0]->link_T_shape.translation() - c.from).norm(), 1e-9) << c.link;
    EXPECT_LT((spheres[1]->link_T_shape.translation() - c.to).norm(), 1e-9) << c.link;
  }
  EXPECT_EQ(arm.links_without_collision(), (std::vector<std::string>{"link5", "flange"}));
  EXPECT_TRUE(arm.collision_notes().empty());
}

TEST(ArmModelCollision, MeshesAreRecordedAndReportedNotLoaded) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("arm_model_mesh_" + std::to_string(::getpid()) + ".urdf");
  std::ofstream(path) << "<robot name='m'><link name='base_link'/><link name='flange'><collision>"
                         "<origin xyz='0 0 0.1'/><geometry><mesh filename='package://arm/meshes/wrist.stl' "
                         "scale='0.001 0.001 0.001'/></geometry></collision><collision><geometry><sphere "
                         "radius='0.05'/></geometry></collision></link><joint name='j' type='revolute'><parent "
                         "link='base_link'/><child link='flange'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' "
                         "velocity='1' effort='1'/></joint></robot>";
  const ArmModel arm(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(arm.collision_shapes().size(), 2u);
  const CollisionShape& mesh = arm.collision_shapes()[0];
  EXPECT_EQ(mesh.type, ShapeType::kMesh);
  EXPECT_FALSE(mesh.supported());
  EXPECT_EQ(mesh.mesh_filename, "package://arm/meshes/wrist.stl");
  EXPECT_NEAR(mesh.mesh_scale.x(), 0.001, 1e-15);
  EXPECT_NEAR(mesh.link_T_shape.translation().z(), 0.1, 1e-15);
  EXPECT_TRUE(arm.collision_shapes()[1].supported());
  ASSERT_EQ(arm.collision_notes().size(), 1u);
  EXPECT_NE(arm.collision_notes()[0].find("package://arm/meshes/wrist.stl"), std::string::npos);
  EXPECT_NE(arm.collision_notes()[0].find("not supported yet"), std::string::npos);
}

// Whether the base point p lies inside a supported primitive of one of `bodies`, posed at q.
bool covered(const ArmModel& arm, const JointVector& q, const Eigen::Vector3d& p, std::initializer_list<int> bodies) {
  for (const CollisionShape& s : arm.collision_shapes()) {
    if (!s.supported() || std::find(bodies.begin(), bodies.end(), s.body) == bodies.end()) continue;
    const Eigen::Isometry3d base_T_shape = arm.fk(q, arm.body_frame(s.body)) * s.body_T_shape;
    if (s.contains(base_T_shape.inverse() * p, 1e-9)) return true;
  }
  return false;
}

// The skeleton check. Body k (0 = the base; k = 1..n the link after joint k with the links
// fixed to it) has as skeleton the straight segment from the origin of its own link (on joint
// k's axis; the base link's origin for k = 0) to the origin of body k+1's link (on joint k+1's
// axis), or to the flange for the last body. 41 points on it must each lie inside a collision
// primitive of body k-1, k or k+1 (a joint's housing belongs to one of the two links it joins),
// at q = 0 and at 50 random joint sets; and each moving body's centre of mass inside one of its
// own primitives. This checks that the primitives cover the chain's straight connections between
// joint origins and its masses, not that they fit the real links' surfaces: the URDFs' comments
// say how conservative they are.
void expect_skeleton_covered(const ArmModel& arm) {
  const int n = arm.dof();
  std::mt19937_64 rng(71);
  int points = 0;
  for (int trial = 0; trial <= 50; ++trial) {
    const JointVector q =
        trial == 0 ? JointVector(JointVector::Zero(n).cwiseMax(arm.limits().lower).cwiseMin(arm.limits().upper))
                   : test::random_q(arm, rng);
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector3d from = arm.fk(q, arm.body_frame(k)).translation();
      const Eigen::Vector3d to = arm.fk(q, k < n ? arm.body_frame(k + 1) : arm.frame("flange")).translation();
      for (int i = 0; i <= 40; ++i, ++points) {
        const Eigen::Vector3d p = from + (to - from) * (i / 40.0);
        EXPECT_TRUE(covered(arm, q, p, {k - 1, k, k + 1}))
            << arm.urdf_path() << ": body " << k << " (" << arm.frame_name(arm.body_frame(k)) << "), point " << i
            << "/40 of its skeleton, q = " << q.transpose();
      }
      if (k > 0 && arm.body(k).mass > 0.0) {
        EXPECT_TRUE(covered(arm, q, arm.fk(q, arm.body_frame(k)) * arm.body(k).com, {k}))
            << arm.urdf_path() << ": centre of mass of body " << k;
      }
    }
  }
  std::printf("%s: %d skeleton points covered\n", arm.urdf_path().c_str(), points);
}

TEST(ArmModelCollision, Ur5ePrimitivesCoverEveryLinksSkeleton) {
  const ArmModel arm(kUr5eUrdf);
  EXPECT_TRUE(arm.collision_notes().empty());
  expect_skeleton_covered(arm);
}

TEST(ArmModelCollision, Fr3PrimitivesCoverEveryLinksSkeleton) {
  const ArmModel arm(kFr3Urdf);
  EXPECT_TRUE(arm.collision_notes().empty());
  expect_skeleton_covered(arm);
}

}  // namespace
}  // namespace wysiwyf::robot
