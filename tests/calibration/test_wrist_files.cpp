// The wrist calibration's files: the readings file (round trip, hostile input refused with
// file:line and what was expected) and the scene file's tool load rewritten in place, read back by
// the scene loader that admittance_sim and the supervisor use.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "scene/scene.hpp"
#include "wrist_calibration/scene_tool_load.hpp"
#include "wrist_calibration/wrist_readings_file.hpp"

namespace wr = wysiwyf::robot;

namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string error_of(const std::string& yaml) {
  try {
    wr::load_wrist_readings_from_string(yaml, "r.yaml", 6);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(WristFiles, ReadingsRoundTrip) {
  wr::WristSample a;
  a.label = "pose 1";
  a.joints = Eigen::VectorXd::LinSpaced(6, -1.0, 1.25);
  a.wrench << 1.5, -2, 11.3431, 0.01, -0.2, 3e-5;
  wr::WristSample b = a;
  b.label = "pose 2";
  b.joints[3] = 0.123456789;
  const auto back = wr::load_wrist_readings_from_string(wr::wrist_readings_yaml({a, b}), "r.yaml", 6);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].label, "pose 2");
  EXPECT_LT((back[1].joints - b.joints).norm(), 1e-8);
  EXPECT_LT((back[0].wrench - a.wrench).norm(), 1e-8);
}

TEST(WristFiles, HostileReadingsAreRefusedWithWhereAndWhat) {
  EXPECT_NE(error_of("readings: 3").find("r.yaml:1:11: readings: expected a list"), std::string::npos)
      << error_of("readings: 3");
  const std::string five = "readings:\n  - {joints: [0, 0, 0, 0, 0], wrench: [0, 0, 0, 0, 0, 0]}\n";
  EXPECT_NE(error_of(five).find("r.yaml:2:14: readings[0] joints: expected a list of 6 numbers"), std::string::npos)
      << error_of(five);
  const std::string nan = "readings:\n  - {joints: [0, 0, 0, 0, 0, 0], wrench: [0, .nan, 0, 0, 0, 0]}\n";
  EXPECT_NE(error_of(nan).find("r.yaml:2:46: readings[0] wrench"), std::string::npos) << error_of(nan);
  EXPECT_NE(error_of(nan).find("expected a finite number"), std::string::npos);
  const std::string key = "readings:\n  - {joint: [0, 0, 0, 0, 0, 0], wrench: [0, 0, 0, 0, 0, 0]}\n";
  EXPECT_NE(error_of(key).find("unknown key 'joint'"), std::string::npos) << error_of(key);
  EXPECT_NE(error_of("readings: [").find("not YAML"), std::string::npos);
  EXPECT_NE(error_of("[1, 2]").find("expected a map with readings"), std::string::npos);
  EXPECT_NE(error_of("readings: []\nextra: 1\n").find("unknown key 'extra'"), std::string::npos);
  EXPECT_THROW(wr::load_wrist_readings("/nonexistent/readings.yaml", 6), std::runtime_error);
}

// The demo's scene with a calibrated tool: the two lines change, their comments and every other
// line stay, and the scene loader reads the new values.
TEST(WristFiles, SceneToolLoadIsRewrittenInPlace) {
  const std::string path = std::string(WYSIWYF_CONFIG_DIR) + "/scenes/display_demo.yaml";
  const std::string before = read(path);
  const std::string after = wr::with_tool_load(before, path, 1.2034, Eigen::Vector3d(0.001, -0.0005, 0.0171));
  const auto scene = wysiwyf::haptics::load_scene_from_string(after, path);
  EXPECT_NEAR(scene.device.tool_mass, 1.2034, 1e-9);
  EXPECT_LT((scene.device.tool_com - Eigen::Vector3d(0.001, -0.0005, 0.0171)).norm(), 1e-9);
  EXPECT_NE(after.find("  tool_mass: 1.2034                # kg carried by the sensor\n"), std::string::npos) << after;
  EXPECT_NE(after.find("# in the sensor frame"), std::string::npos);
  std::istringstream a(before), b(after);
  int changed = 0, lines = 0;
  for (std::string la, lb; std::getline(a, la) && std::getline(b, lb); ++lines) changed += la != lb;
  EXPECT_EQ(changed, 2);
  EXPECT_GT(lines, 30);
}

TEST(WristFiles, SceneWithoutToolLinesGetsThemAndBadScenesAreRefused) {
  const std::string scene =
      "scene: 1\nname: s\nbodies:\n  cube: {size: [0.2, 0.2, 0.2], mass: 1, position: [0, 0, 0.1]}\n"
      "device:\n  body: cube\n  face: +x\n";
  const std::string after = wr::with_tool_load(scene, "s.yaml", 0.5, Eigen::Vector3d(0, 0, 0.01));
  EXPECT_NEAR(wysiwyf::haptics::load_scene_from_string(after, "s.yaml").device.tool_mass, 0.5, 1e-12);
  try {
    wr::with_tool_load("scene: 1\nname: s\n", "s.yaml", 0.5, Eigen::Vector3d::Zero());
    ADD_FAILURE() << "a scene without a device was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("s.yaml: no device: section"), std::string::npos) << e.what();
  }
  EXPECT_THROW(wr::with_tool_load("device: {body: cube}\n", "s.yaml", 0.5, Eigen::Vector3d::Zero()),
               std::runtime_error);
  EXPECT_THROW(wr::with_tool_load(scene, "s.yaml", -1, Eigen::Vector3d::Zero()), std::runtime_error);
}
