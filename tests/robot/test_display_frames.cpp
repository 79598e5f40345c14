// The frames the display needs on any arm: every shipped arm has them, fixed to its last body,
// and a lab's URDF without one is refused by name, file and purpose.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "arm_model/display_frames.hpp"
#include "arm_model_test_util.hpp"

namespace wysiwyf::robot::test {
namespace {

TEST(DisplayFrames, EveryShippedArmHasEveryFrameOnItsLastBody) {
  for (const std::string& urdf : {kPumaUrdf, kUr5eUrdf, kFr3Urdf}) {
    const auto model = load_display_arm(urdf, "dev");
    ASSERT_TRUE(model) << urdf;
    for (const DisplayFrame& f : display_frames()) {
      EXPECT_EQ(model->frame_body(model->frame(f.name)), model->dof()) << urdf << ": " << f.name;
      EXPECT_FALSE(display_frame_purpose(f.name).empty());
    }
  }
  EXPECT_TRUE(display_frame_purpose("link3").empty());
}

// ur5e.urdf less the link `name` and the fixed joint that carries it (with no children of its own).
std::string without_link(const std::string& name) {
  std::ifstream in(kUr5eUrdf);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  s = std::regex_replace(s, std::regex("<link name=\"" + name + "\"/>"), "");
  s = std::regex_replace(s, std::regex("<link name=\"" + name + "\">[\\s\\S]*?</link>"), "");
  s = std::regex_replace(s, std::regex("<joint name=\"" + name + "_joint\"[\\s\\S]*?</joint>"), "");
  const auto path =
      std::filesystem::temp_directory_path() / ("display_frames_" + std::to_string(getpid()) + "_" + name + ".urdf");
  std::ofstream(path) << s;
  return path.string();
}

TEST(DisplayFrames, AUrdfWithoutAFrameIsRefusedByNameFileAndPurpose) {
  for (const std::string name : {"knob", "marker_2"}) {
    const std::string path = without_link(name);
    try {
      load_display_arm(path, "flange");
      ADD_FAILURE() << "loaded " << path << " without " << name;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("no link '" + name + "'"), std::string::npos) << what;
      EXPECT_NE(what.find(display_frame_purpose(name)), std::string::npos) << what;
    }
    std::filesystem::remove(path);
  }
}

TEST(DisplayFrames, AFileThatIsNoUrdfGetsTheModelsOwnError) {
  const auto path = std::filesystem::temp_directory_path() / ("display_frames_" + std::to_string(getpid()) + ".urdf");
  std::ofstream(path) << "<robot name=\"x\"><link";
  EXPECT_THROW(load_display_arm(path.string(), "dev"), std::runtime_error);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace wysiwyf::robot::test
