// overlay: the mode and the user's force drawn in the top-left corner, nothing else touched; the
// force bar as long as the force (the reading less the tool's weight) is; show: false and no
// mode yet pass the image through unchanged.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::render {

namespace {

msg::Image grey_image() {
  msg::Image img;
  img.width(640), img.height(480), img.encoding("rgb8"), img.step(640 * 3);
  img.data().assign(640 * 480 * 3, 128);
  return img;
}

cv::Mat view(msg::Image& m) { return cv::Mat(480, 640, CV_8UC3, m.data().data()); }

struct OverlayRun {
  Harness h;
  Output<msg::Image> image;
  Output<msg::DisplayMode> mode;
  Output<msg::WrenchStamped> wrench;
  Output<msg::PoseStamped> device;
  Input<msg::Image> out;
  explicit OverlayRun(const std::string& params)
      : h("overlay", params, 25),
        image(h.feed<msg::Image>("image")),
        mode(h.feed<msg::DisplayMode>("mode")),
        wrench(h.feed<msg::WrenchStamped>("wrench")),
        device(h.feed<msg::PoseStamped>("device_pose")),
        out(h.watch<msg::Image>("image_out")) {
    h.activate();
  }
  // The plate facing +x (dev z along base x), the sensor reading the tool's weight plus a push
  // of `push` newtons along -z of the plate.
  msg::Image frame(double push, bool with_mode = true) {
    if (with_mode) {
      msg::DisplayMode m;
      m.mode(msg::MODE_ADMITTANCE);
      mode.write(m);
    }
    Eigen::Isometry3d base_T_dev = Eigen::Isometry3d::Identity();
    base_T_dev.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    msg::PoseStamped d;
    msgs::to_msg(base_T_dev, d.pose());
    device.write(d);
    // The tool's weight in the sensor frame (sensor axes = the plate's: scene's dev_T_sensor has no turn).
    const Eigen::Vector3d weight = base_T_dev.linear().transpose() * Eigen::Vector3d(0, 0, -9.81 * 1.1563);
    msg::WrenchStamped w;
    msgs::to_msg(Eigen::Vector3d(weight + Eigen::Vector3d(0, 0, -push)), w.wrench().force());
    wrench.write(w);
    image.write(grey_image());
    h.tick(Time{t_ += 40'000'000});
    msg::Image o;
    EXPECT_TRUE(out.take_latest(o));
    return o;
  }
  std::int64_t t_ = 0;
};

// Pixels that differ from the grey input, in and outside the top-left 300 x 120 px.
std::pair<int, int> changed(msg::Image& o) {
  cv::Mat diff;
  cv::absdiff(view(o), cv::Scalar(128, 128, 128), diff);
  cv::Mat any;
  cv::cvtColor(diff, any, cv::COLOR_RGB2GRAY);
  const int inside = cv::countNonZero(any(cv::Rect(0, 0, 300, 120)));
  return {inside, cv::countNonZero(any) - inside};
}

// The force bar's filled pixels: admittance orange (255, 170, 40) on its row.
int bar_pixels(msg::Image& o) {
  cv::Mat orange;
  cv::inRange(view(o), cv::Scalar(250, 165, 35), cv::Scalar(255, 175, 45), orange);
  return cv::countNonZero(orange(cv::Rect(110, 20, 200, 50)));
}

}  // namespace

TEST(Overlay, DrawsTheModeAndTheForceInTheCornerOnly) {
  OverlayRun run("{scene: scenes/display_demo.yaml, full_scale: 20}");
  msg::Image five = run.frame(5.0), ten = run.frame(10.0);
  const auto [inside, outside] = changed(ten);
  EXPECT_GT(inside, 5000);  // the dark panel and the text
  EXPECT_EQ(outside, 0);
  const int bar5 = bar_pixels(five), bar10 = bar_pixels(ten);
  EXPECT_GT(bar5, 50);
  EXPECT_NEAR(static_cast<double>(bar10) / bar5, 2.0, 0.25) << bar5 << " vs " << bar10;
}

TEST(Overlay, SwitchedOffOrBeforeAModeTheImagePassesUnchanged) {
  {
    OverlayRun run("{show: false}");
    msg::Image o = run.frame(5.0);
    EXPECT_EQ(changed(o), std::make_pair(0, 0));
  }
  OverlayRun run("{}");
  msg::Image o = run.frame(5.0, false);
  EXPECT_EQ(changed(o), std::make_pair(0, 0));
}

}  // namespace wysiwyf::render
