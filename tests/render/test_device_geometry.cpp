// DeviceGeometry on every arm the project ships (PUMA 560, UR5e, FR3): a shape for every collision
// box, cylinder and sphere of the URDF, the arm's links, the plate, the knob and the four lamps
// told apart by link; each posed as fk(its link) * its collision origin; the PUMA's plate, knob and
// lamps at their sizes; and a URDF without a lamp's shape refused by link and file.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <unistd.h>

#include "arm_model/arm_model.hpp"
#include "device_geometry/device_geometry.hpp"

namespace wysiwyf::render {
using namespace robot;  // the arm model's types, which the geometry reads
namespace {

std::string urdf(const char* arm) { return std::string(WYSIWYF_CONFIG_DIR) + "/robots/" + arm + ".urdf"; }

class DeviceGeometryOn : public ::testing::TestWithParam<const char*> {};

TEST_P(DeviceGeometryOn, DrawsEveryLinksCollisionShapesAndTellsTheDeviceApart) {
  const ArmModel arm(urdf(GetParam()), "flange");
  const DeviceGeometry device(arm);
  std::vector<const CollisionShape*> supported;
  for (const CollisionShape& s : arm.collision_shapes())
    if (s.supported()) supported.push_back(&s);
  ASSERT_EQ(device.shapes().size(), supported.size());
  int plate = 0, knob = 0, arm_shapes = 0;
  std::array<int, 4> lamps{};
  for (std::size_t i = 0; i < supported.size(); ++i) {
    const DeviceShape& shape = device.shapes()[i];
    const CollisionShape& c = *supported[i];
    EXPECT_EQ(shape.link, c.link);
    switch (shape.part) {
      case DeviceShape::Part::kPlate:
        ++plate;
        EXPECT_EQ(c.link, "dev");
        break;
      case DeviceShape::Part::kKnob:
        ++knob;
        EXPECT_EQ(c.link, "knob");
        break;
      case DeviceShape::Part::kLamp:
        ASSERT_TRUE(shape.index >= 0 && shape.index < 4);
        ++lamps[static_cast<std::size_t>(shape.index)];
        EXPECT_EQ(c.link, "marker_" + std::to_string(shape.index));
        break;
      case DeviceShape::Part::kArm: ++arm_shapes; break;
    }
    switch (c.type) {
      case ShapeType::kBox:
        EXPECT_EQ(shape.kind, DeviceShape::Kind::kBox);
        EXPECT_LT((shape.size.cast<double>() - 0.5 * c.box_size).norm(), 1e-6);
        break;
      case ShapeType::kCylinder:
        EXPECT_EQ(shape.kind, DeviceShape::Kind::kCylinder);
        EXPECT_NEAR(shape.size.x(), c.radius, 1e-6);
        EXPECT_NEAR(shape.size.y(), 0.5 * c.length, 1e-6);
        break;
      case ShapeType::kSphere:
        EXPECT_EQ(shape.kind, DeviceShape::Kind::kSphere);
        EXPECT_NEAR(shape.size.x(), c.radius, 1e-6);
        break;
      case ShapeType::kMesh: ADD_FAILURE() << "a mesh drawn"; break;
    }
  }
  EXPECT_EQ(plate, 1);
  EXPECT_EQ(knob, 1);
  EXPECT_EQ(lamps, (std::array<int, 4>{1, 1, 1, 1}));
  EXPECT_GT(arm_shapes, arm.dof());
  // Every link on the chain that has collision elements is drawn.
  for (int k = 0; k <= arm.dof(); ++k) {
    const std::string& link = arm.frame_name(arm.body_frame(k));
    const auto& without = arm.links_without_collision();
    if (std::find(without.begin(), without.end(), link) != without.end()) continue;
    EXPECT_TRUE(std::any_of(device.shapes().begin(), device.shapes().end(),
                            [&](const DeviceShape& s) { return s.link == link && s.part == DeviceShape::Part::kArm; }))
        << GetParam() << ": link " << link;
  }
}

TEST_P(DeviceGeometryOn, PosesEachShapeAtItsLinksPoseTimesItsCollisionOrigin) {
  const ArmModel arm(urdf(GetParam()), "flange");
  const DeviceGeometry device(arm);
  std::vector<const CollisionShape*> supported;
  for (const CollisionShape& s : arm.collision_shapes())
    if (s.supported()) supported.push_back(&s);
  std::mt19937_64 rng(17);
  std::vector<Eigen::Isometry3d> poses;
  for (int trial = 0; trial < 10; ++trial) {
    JointVector q(arm.dof());
    for (int j = 0; j < arm.dof(); ++j)
      q[j] = std::uniform_real_distribution<double>(std::max(arm.limits().lower[j], -M_PI),
                                                    std::min(arm.limits().upper[j], M_PI))(rng);
    device.poses(q, poses);
    ASSERT_EQ(poses.size(), supported.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const Eigen::Isometry3d expected = arm.fk(q, arm.frame(supported[i]->link)) * supported[i]->link_T_shape;
      EXPECT_LT((poses[i].matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-12) << supported[i]->link;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Arms, DeviceGeometryOn, ::testing::Values("puma560", "ur5e", "fr3"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

// The PUMA's device as built: the plate 20 x 20 x 1 cm behind dev's z = 0, the knob 3 cm across
// and 4 cm out of the face, the lamps 6 mm domes on the face 8 cm from its centre in x and y.
TEST(DeviceGeometry, ThePumasPlateKnobAndLampsAreTheDevicesSizesAndPlaces) {
  const ArmModel arm(urdf("puma560"), "flange");
  const DeviceGeometry device(arm);
  const JointVector q = (JointVector(6) << 0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254).finished();
  std::vector<Eigen::Isometry3d> poses;
  device.poses(q, poses);
  const Eigen::Isometry3d dev_T_base = arm.fk(q, arm.frame("dev")).inverse();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const DeviceShape& s = device.shapes()[i];
    const Eigen::Isometry3d dev_T_shape = dev_T_base * poses[i];
    if (s.part == DeviceShape::Part::kPlate) {
      EXPECT_LT((s.size - Eigen::Vector3f(0.1f, 0.1f, 0.005f)).norm(), 1e-7);
      EXPECT_LT((dev_T_shape.translation() - Eigen::Vector3d(0, 0, -0.005)).norm(), 1e-12);
    } else if (s.part == DeviceShape::Part::kKnob) {
      EXPECT_LT((s.size - Eigen::Vector3f(0.015f, 0.02f, 0.0f)).norm(), 1e-7);
      EXPECT_LT((dev_T_shape.translation() - Eigen::Vector3d(0, 0, 0.02)).norm(), 1e-12);
    } else if (s.part == DeviceShape::Part::kLamp) {
      EXPECT_FLOAT_EQ(s.size.x(), 0.006f);
      const double x = (s.index == 0 || s.index == 3) ? 0.08 : -0.08, y = s.index < 2 ? 0.08 : -0.08;
      EXPECT_LT((dev_T_shape.translation() - Eigen::Vector3d(x, y, 0)).norm(), 1e-12) << s.index;
    }
  }
}

// A lab's URDF whose lamps carry no collision sphere cannot be drawn for the camera: refused with
// the link, what it is and the file.
TEST(DeviceGeometry, AUrdfWithoutALampsShapeIsRefusedByLinkAndFile) {
  const std::string text = [] {
    std::ifstream in(urdf("puma560"));
    std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string lamp = "<collision><geometry><sphere radius=\"0.006\"/></geometry></collision>";
    const std::string name = "<link name=\"marker_2\">";
    const auto at = all.find(lamp, all.find(name));
    if (at != std::string::npos) all.erase(at, lamp.size());
    return all;
  }();
  const auto path =
      std::filesystem::temp_directory_path() / ("device_geometry_" + std::to_string(::getpid()) + ".urdf");
  std::ofstream(path) << text;
  const ArmModel arm(path.string(), "flange");
  std::filesystem::remove(path);
  try {
    const DeviceGeometry device(arm);
    ADD_FAILURE() << "a URDF without marker_2's shape accepted";
  } catch (const std::invalid_argument& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find("'marker_2' (a lamp on the plate)"), std::string::npos) << why;
    EXPECT_NE(why.find(path.string()), std::string::npos) << why;
  }
}

}  // namespace
}  // namespace wysiwyf::render
