// The demo's own figures, held by a test: demo-sim.yaml (what scripts/demo runs) whole, on the
// sim clock, and every headline figure of its summary.json checked over every image and every
// millisecond of contact, first to last. Each figure has its goal and, where the goal is not yet
// met, the figure this code reaches as the bound, so a change that makes any of them worse fails
// here (a tracker re-acquiring on the wrong pose took visual registration from 1.25 to 410 mm and
// no test noticed).
#include <gtest/gtest.h>

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
  const json& visual = s.at("visual_registration");
  const json& haptic = s.at("haptic_registration").at("run");
  const json& bleed = s.at("bleed_through");
  // Every image of the run is measured (25 fps over 11.6 s), none left out at the end.
  EXPECT_GE(visual.at("images").get<int>(), 285);
  EXPECT_GE(bleed.at("images").get<int>(), 285);
  EXPECT_GE(haptic.at("samples").get<int>(), 2500);
  check({
      {"visual registration p99, mm", visual.at("p99_mm"), 1.0, 1.0},
      {"visual registration max, mm", visual.at("max_mm"), 2.0, 2.0},
      {"haptic registration while attached p99, mm (the impact included)", haptic.at("p99_mm"), 1.0, 2.2},
      {"haptic registration while attached max, mm", haptic.at("max_mm"), 1.5, 2.5},
      {"bleed-through: images with real device pixels shown", bleed.at("images_with_any"), 0, 9},
      {"bleed-through: most device pixels in one image", bleed.at("max_px"), 0, 27},
  });
}

}  // namespace
}  // namespace wysiwyf::test
