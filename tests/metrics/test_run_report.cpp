// The run report: display_metrics writes summary.json and the CSV time series into its folder,
// they parse and carry what was fed (the cube's path, the force, the modes, a known latency);
// scripts/run-report draws the plots with gnuplot (non-empty images) and an index.html that
// shows them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

namespace {

std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace

TEST(RunReport, TheFilesAreWrittenParseAndThePlotsAreImages) {
  constexpr std::int64_t kMs = 1'000'000;
  const std::filesystem::path dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / "run_report";
  std::filesystem::remove_all(dir);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  Harness h("display_metrics", "{scene: scenes/display_demo.yaml, report: " + dir.string() + "}", 100, &loader);
  auto objects = h.feed<msg::ObjectState>("objects");
  auto device = h.feed<msg::PoseStamped>("device_pose");
  auto mode = h.feed<msg::DisplayMode>("mode");
  auto composite = h.feed<msg::Image>("composite");
  auto shown = h.feed<msg::Image>("shown");
  h.activate();
  const int ticks = 200;  // 2 s at 100 Hz: surface mode for 1 s, then admittance; the cube moves in x
  for (int k = 0; k < ticks; ++k) {
    const std::int64_t t = k * 10 * kMs;
    msg::ObjectState o;
    fill_header(o.header(), t, k, "base");
    o.child_frame_id("cube");
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.6 + 0.05 * t * 1e-9, 0, 0.1);
    msgs::to_msg(T, o.pose());
    objects.write(o);
    msg::PoseStamped p;
    fill_header(p.header(), t, k, "base");
    msgs::to_msg(T, p.pose());
    device.write(p);
    msg::DisplayMode m;
    fill_header(m.header(), t, k, "");
    m.mode(k < 100 ? msg::MODE_SURFACE : msg::MODE_ADMITTANCE);
    mode.write(m);
    if (k % 4 == 0) {  // a 25 Hz camera; each composite made 40 ms after its frame
      msg::Image c, a;
      fill_header(c.header(), t, static_cast<std::uint64_t>(k), "eye");
      fill_header(a.header(), t - 40 * kMs, static_cast<std::uint64_t>(k), "eye");
      a.width(2), a.height(2), a.encoding("mono8"), a.step(2), a.data().assign(4, 0);
      if (k >= 4) composite.write(c), shown.write(a);
    }
    h.tick(Time{t});
  }
  h.deactivate();

  ASSERT_TRUE(YAML::LoadFile((dir / "summary.json").string()).IsMap());
  const auto series = read_csv(dir / "timeseries.csv");
  ASSERT_EQ(series.size(), static_cast<std::size_t>(ticks + 1));
  EXPECT_EQ(series[0][0], "t_s");
  EXPECT_EQ(series[0].size(), 12u);
  EXPECT_EQ(series[150].size(), 12u);
  EXPECT_NEAR(std::stod(series[150][5]), 0.6 + 0.05 * 1.49, 1e-6) << "cube x at t = 1.49 s";
  EXPECT_EQ(series[50][8], "1") << "surface mode";
  EXPECT_EQ(series[150][8], "2") << "admittance mode";
  const auto latency = read_csv(dir / "latency.csv");
  ASSERT_GT(latency.size(), 40u);
  for (std::size_t i = 1; i < latency.size(); ++i) EXPECT_NEAR(std::stod(latency[i][1]), 40.0, 1e-6);

  const std::string command = std::string(WYSIWYF_SOURCE_DIR) + "/scripts/run-report " + dir.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  for (const char* png : {"force_and_cube.png", "registration.png", "latency.png"}) {
    const cv::Mat image = cv::imread((dir / png).string());
    ASSERT_FALSE(image.empty()) << png;
    EXPECT_GT(image.cols, 500) << png;
    cv::Scalar mean, stddev;
    cv::meanStdDev(image, mean, stddev);
    EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 10.0) << png << " is one flat colour";
  }
  std::ifstream page(dir / "index.html");
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  for (const char* png : {"force_and_cube.png", "registration.png", "latency.png"})
    EXPECT_NE(html.find(png), std::string::npos) << png;
}

}  // namespace wysiwyf::test
