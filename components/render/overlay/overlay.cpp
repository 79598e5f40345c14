// overlay: what the display is doing, drawn small in a corner of what the user sees: the mode
// (surface: where the plate is going and whether it is there; admittance: the user pushing;
// fault: why), and the user's force on the plate (the wrist reading less the tool's weight, as
// the supervisor judges contact) as a number and a bar. show: false passes the image through
// unchanged (a recording without it); so does an image that comes before any mode.
#include <algorithm>
#include <array>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "image/image_view.hpp"
#include "scene/scene.hpp"
#include "scene/tool_load.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::render {

namespace {

const char* mode_name(msg::DisplayModeKind m) {
  switch (m) {
    case msg::MODE_SURFACE: return "SURFACE";
    case msg::MODE_ADMITTANCE: return "ADMITTANCE";
    case msg::MODE_FAULT: return "FAULT";
    default: return "IDLE";
  }
}

const char* planner_state(msg::PlannerState s) {
  switch (s) {
    case msg::PLAN_MOVING: return "moving";
    case msg::PLAN_IN_PLACE: return "in place";
    case msg::PLAN_WAITING: return "waiting (hand near)";
    case msg::PLAN_UNREACHABLE: return "unreachable";
    case msg::PLAN_FAULT: return "fault";
    default: return "idle";
  }
}

// The mode's colour (RGB).
cv::Scalar mode_colour(msg::DisplayModeKind m) {
  switch (m) {
    case msg::MODE_SURFACE: return {90, 200, 255};
    case msg::MODE_ADMITTANCE: return {255, 170, 40};
    case msg::MODE_FAULT: return {255, 60, 60};
    default: return {200, 200, 200};
  }
}

}  // namespace

class Overlay final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("the display's mode and the user's force, drawn small in a corner of the image");
    show_ = ctx.param<bool>("show", true, "draw the overlay (false: the image passes unchanged)");
    scene_path_ = ctx.param<std::string>("scene", "scenes/cube_against_wall.yaml",
                                         "scene file: the tool's mass and the sensor's place on the plate");
    full_scale_ = ctx.param<double>("full_scale", 20.0, "N at the force bar's end", Range{1, 1000});
    image_in_ = ctx.input<msg::Image>("image", "what the user sees (the compositor's), rgb8", Qos::sensor(2));
    mode_in_ = ctx.input<msg::DisplayMode>("mode", "the display's mode (the supervisor)", Qos::reliable(8));
    planner_in_ = ctx.input<msg::PlannerStatus>("planner", "optional: the surface planner's status",
                                                Qos::reliable(64).optional_input());
    // 1 kHz streams read at the image rate: room for one frame's samples (the latest is drawn).
    wrench_in_ = ctx.input<msg::WrenchStamped>("wrench", "the wrist sensor's reading", Qos::sensor(64));
    device_in_ = ctx.input<msg::PoseStamped>("device_pose", "the plate's pose base_T_dev", Qos::sensor(64));
    image_out_ = ctx.output<msg::Image>("image_out", "the image with the overlay, rgb8", Qos::sensor(2));
    try {
      scene_ = haptics::load_scene(find_config_file(scene_path_));
    } catch (const std::exception& e) {
      ctx.reject("scene", e.what());
    }
  }

  void tick(Time) override {
    while (mode_in_.take(mode_msg_)) have_mode_ = true;
    while (planner_in_.take(planner_msg_)) have_planner_ = true;
    while (take_checked(wrench_in_, wrench_msg_))
      reading_ = {msgs::to_eigen(wrench_msg_.wrench().force()), msgs::to_eigen(wrench_msg_.wrench().torque())},
      have_reading_ = true;
    while (take_checked(device_in_, device_msg_)) device_ = msgs::to_isometry(device_msg_.pose()), have_device_ = true;
    if (!image_in_.take_latest(image_)) return;
    if (const std::string bad = vision::image::problem(image_, {"rgb8"}); !bad.empty()) return reject(image_in_, bad);
    if (show_ && have_mode_) draw(vision::image::view(image_));
    image_out_.write(image_);
  }

 private:
  void draw(cv::Mat img) {
    const double scale = std::clamp(img.rows / 480.0, 0.5, 3.0);
    const int line = static_cast<int>(std::lround(18 * scale)), pad = static_cast<int>(std::lround(6 * scale));
    const int width = static_cast<int>(std::lround(250 * scale));
    std::array<std::string, 3> text;
    const msg::DisplayModeKind mode = mode_msg_.mode();
    text[0] = mode_name(mode);
    if (mode == msg::MODE_FAULT) text[0] += ": " + std::string(mode_msg_.reason().c_str()).substr(0, 30);
    if (have_planner_ && mode == msg::MODE_SURFACE && planner_msg_.feature().size() > 0)
      text[1] = std::string(planner_msg_.feature().c_str()) + ", " + planner_state(planner_msg_.state());
    double force = -1;
    if (have_reading_ && have_device_) {
      force = haptics::user_load(reading_, device_, scene_.device, scene_.gravity).force.norm();
      char buf[32];
      std::snprintf(buf, sizeof buf, "force %.1f N", force);
      text[2] = buf;
    }
    const int rows = 1 + !text[1].empty() + (force >= 0);
    const cv::Rect box(pad, pad, width, rows * line + 2 * pad + (force >= 0 ? pad : 0));
    cv::Mat region = img(box & cv::Rect(0, 0, img.cols, img.rows));
    region *= 0.45;  // a dark panel behind the text: readable on any scene
    const double font = 0.45 * scale;
    const int thick = std::max(1, static_cast<int>(std::lround(scale)));
    int y = pad + line - pad / 2;
    cv::putText(img, text[0], {2 * pad, y}, cv::FONT_HERSHEY_SIMPLEX, font, mode_colour(mode), thick, cv::LINE_AA);
    if (!text[1].empty()) {
      y += line;
      cv::putText(img, text[1], {2 * pad, y}, cv::FONT_HERSHEY_SIMPLEX, font, {230, 230, 230}, thick, cv::LINE_AA);
    }
    if (force >= 0) {
      y += line;
      cv::putText(img, text[2], {2 * pad, y}, cv::FONT_HERSHEY_SIMPLEX, font, {230, 230, 230}, thick, cv::LINE_AA);
      const int bar_x = 2 * pad + static_cast<int>(std::lround(110 * scale)), bar_w = width - bar_x;
      const cv::Rect bar(bar_x, y - line / 2, bar_w, line / 2);
      cv::rectangle(img, bar, {120, 120, 120}, 1);
      const int filled = static_cast<int>(std::lround(bar_w * std::min(1.0, force / full_scale_)));
      if (filled > 0) cv::rectangle(img, cv::Rect(bar.x, bar.y, filled, bar.height), mode_colour(mode), cv::FILLED);
    }
  }

  bool show_ = true;
  std::string scene_path_;
  double full_scale_ = 20;
  haptics::Scene scene_;
  haptics::SensorReading reading_;
  Eigen::Isometry3d device_ = Eigen::Isometry3d::Identity();
  bool have_mode_ = false, have_planner_ = false, have_reading_ = false, have_device_ = false;
  msg::Image image_;
  msg::DisplayMode mode_msg_;
  msg::PlannerStatus planner_msg_;
  msg::WrenchStamped wrench_msg_;
  msg::PoseStamped device_msg_;
  Input<msg::Image> image_in_;
  Input<msg::DisplayMode> mode_in_;
  Input<msg::PlannerStatus> planner_in_;
  Input<msg::WrenchStamped> wrench_in_;
  Input<msg::PoseStamped> device_in_;
  Output<msg::Image> image_out_;
};

}  // namespace wysiwyf::render

WYSIWYF_COMPONENT(wysiwyf::render::Overlay, "overlay")
