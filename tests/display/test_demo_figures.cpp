// The demo's own figures, held by a test: demo-sim.yaml (what scripts/demo runs) whole, on the
// sim clock, and every headline goal of config/goals/demo-sim.json checked against its
// summary.json over every image and every millisecond of contact, first to last, so a change that
// makes any of them worse fails here (a tracker re-acquiring on the wrong pose once took visual
// registration from 1.25 to 410 mm and no test noticed). demo-stereo.yaml's bleed-through and
// contacts too; where a goal is not yet met, the figure this code reaches is the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "demo_runs.hpp"

namespace wysiwyf::test {
namespace {

using json = nlohmann::json;

// A figure of the run: at most `bound`; `goal` is what the product promises (bound < goal where
// the goal is not met yet: then the bound is today's figure, and the test says so).
struct Figure {
  std::string what;
  double value = 0;
  double goal = 0;
  double bound = 0;
};

void check(const std::vector<Figure>& figures) {
  for (const Figure& f : figures) {
    std::printf("[measured] %s: %.4g (goal <= %.4g: %s)\n", f.what.c_str(), f.value, f.goal,
                f.value <= f.goal ? "met" : "NOT YET MET, held at its present figure");
    EXPECT_LE(f.value, f.bound) << f.what << ": worse than this code reaches (goal " << f.goal << ")";
  }
}

std::filesystem::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir =
      std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

json read_summary(const std::filesystem::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << "no " << file;
  return json::parse(in, nullptr, false);
}

// The figure at `path` (keys into the summary), or NaN where it is not there.
double at(const json& summary, const json& path) {
  const json* v = &summary;
  for (const auto& key : path) {
    if (!v->is_object() || !v->contains(key.get<std::string>())) return std::nan("");
    v = &(*v)[key.get<std::string>()];
  }
  return v->is_number() ? v->get<double>() : std::nan("");
}

TEST(DemoFigures, TheSimulatedExperimentHitsEveryContactAndHoldsItsRegistrationFromFirstImageToLast) {
  const auto dir = scratch();
  const std::string text =
      run_demo_hitting_every_contact("demo-sim.yaml",
                                     {"domain=78", "record.params.path=" + (dir / "demo.mp4").string(),
                                      "metrics.params.summary=" + (dir / "summary.json").string()},
                                     2);
  EXPECT_NE(text.find("[supervisor] surface -> admittance"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "demo.mp4"));
  const json s = read_summary(dir / "summary.json");
  ASSERT_TRUE(s.is_object()) << "summary.json is not JSON";
  // Every image of the run is measured (25 fps over 11.6 s), none left out at the end.
  EXPECT_GE(s.at("visual_registration").at("images").get<int>(), 285);
  EXPECT_GE(s.at("bleed_through").at("images").get<int>(), 285);
  EXPECT_GE(s.at("haptic_registration").at("run").at("samples").get<int>(), 2500);
  // The goals scripts/demo prints, all met: each is its own bound.
  std::ifstream goals_file(std::string(WYSIWYF_CONFIG_DIR) + "/goals/demo-sim.json");
  const json goals = json::parse(goals_file, nullptr, false);
  ASSERT_TRUE(goals.is_object() && goals.contains("goals")) << "config/goals/demo-sim.json";
  std::vector<Figure> figures;
  for (const json& g : goals.at("goals")) {
    const double goal = g.at("at_most").get<double>();
    figures.push_back({g.at("what").get<std::string>(), at(s, g.at("path")), goal, goal});
  }
  ASSERT_EQ(figures.size(), 6u);
  check(figures);
  // The user still feels the impact: the push into the wall peaks within 10 % of the 7.92 N it did
  // when the setpoint stopped with the object, before it braked ahead.
  const json& first = s.at("haptic_registration").at("attachments").at(0);
  EXPECT_NEAR(first.at("peak_force_n").get<double>(), 7.92, 0.79);
}

// The stereo hand (display/hand-stereo.yaml): no device pixel shown in any image, and its contacts.
TEST(DemoFigures, TheStereoDemoShowsNoDevicePixelAndHoldsItsContacts) {
  const auto dir = scratch();
  const std::string text =
      run_demo("demo-stereo.yaml", {"domain=86", "record.params.path=" + (dir / "demo.mp4").string(),
                                    "metrics.params.summary=" + (dir / "summary.json").string()});
  const json s = read_summary(dir / "summary.json");
  ASSERT_TRUE(s.is_object()) << "summary.json is not JSON";
  int hits = 0;
  for (const json& c : s.at("contacts")) hits += c.at("hit").get<bool>() ? 1 : 0;
  EXPECT_GE(s.at("bleed_through").at("images").get<int>(), 280);
  check({
      {"bleed-through: images with real device pixels shown", at(s, {"bleed_through", "images_with_any"}), 0, 0},
      // contact 2 is missed by 28 mm: the keyed hand's centre is 10 cm behind the fingertip, so
      // the planner keeps 15 cm for it (Z_d) and, with the hand within 40 cm, ISO/TS 15066 lets
      // the plate move at 0.07 m/s: it is still on its way when the finger arrives
      {"contacts missed of 2", 2.0 - hits, 0, 1},
  });
}

}  // namespace
}  // namespace wysiwyf::test
