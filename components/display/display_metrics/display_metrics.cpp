// display_metrics: what the display promised, measured against the truth. A thin component over
// Measurements, one part per measurement with its own state: it takes the inputs, hands each
// sample to the parts that use it, and writes what they measured: ContactReports on `contacts`,
// HapticRegistrations on `registration`, log lines, and with `report` the run report
// (timeseries.csv, latency.csv, summary.json; with `summary`, summary.json elsewhere too).
#include <fstream>
#include <optional>

#include "image/image_view.hpp"
#include "measurements.hpp"
#include "run_report.hpp"
#include "scene/scene.hpp"
#include "scene/tool_load.hpp"
#include "wysiwyf/camera_info.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::display {

namespace {

std::int64_t stamp(const std_msgs::Header& h, Time now) { return h.stamp_ns() ? h.stamp_ns() : now.ns; }
std::int64_t nanoseconds(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

}  // namespace

class DisplayMetrics final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("measures each contact: hit or miss, plate still before the finger, plate offset from the feature");
    const auto scene_path = ctx.param<std::string>("scene", "scenes/display_demo.yaml", "scene file with its features");
    measured_.contacts = ContactOutcomes(
        ctx.param<double>("still_speed", 0.002, "m/s: the plate slower than this is still", Range{1e-5, 1}));
    measured_.poses = PoseHistory(nanoseconds(
        ctx.param<double>("history", 10.0, "s of plate and object poses kept (events may come late)", Range{1, 600})));
    events_in_ = ctx.input<msg::UserEvent>("events", "the user's touches and misses (user_sim)", Qos::reliable(64));
    device_in_ = ctx.input<msg::PoseStamped>("device_pose", "the plate's true pose base_T_dev", Qos::reliable(64));
    objects_in_ = ctx.input<msg::ObjectState>("objects", "the virtual objects", Qos::reliable(64));
    summary_path_ = ctx.param<std::string>(
        "summary", "", "a JSON file written at the end with every figure (units in the keys); empty: none");
    report_dir_ = ctx.param<std::string>(
        "report", "",
        "a folder for the run report: summary.json, timeseries.csv (every tick), latency.csv; scripts/run-report "
        "adds the plots and index.html; empty: none");
    setpoint_in_ = ctx.input<msg::CartesianSetpoint>("setpoint",
                                                     "optional: the arm's setpoint (the supervisor's), for the "
                                                     "sensor-to-setpoint latency and the setpoint-to-motion "
                                                     "lag",
                                                     Qos::reliable(256).optional_input());
    measured_.setpoint_timing = SetpointTiming(ctx.param<double>(
        "lag_min_speed", 0.02, "m/s: setpoints commanding motion at least this fast are timed to the plate",
        Range{1e-4, 10}));
    mode_in_ = ctx.input<msg::DisplayMode>("mode", "optional: the display's mode (the supervisor's), for the report",
                                           Qos::reliable(16).optional_input());
    measured_.haptic = AttachmentRegistration(nanoseconds(
        ctx.param<double>("onset_window", 0.1, "s after attaching counted as the push's onset", Range{0.001, 10})));
    attach_in_ = ctx.input<msg::Attachment>(
        "attach", "optional: where the device holds the virtual object (the supervisor's): haptic registration",
        Qos::reliable(16).optional_input());
    tracked_in_ = ctx.input<msg::PoseStamped>(
        "eye_T_base", "optional: the camera pose the display draws from (the tracker's), for visual registration",
        Qos::reliable(16).optional_input());
    true_in_ = ctx.input<msg::PoseStamped>("true_eye_T_base", "optional: the true camera pose (camera_sim's)",
                                           Qos::reliable(16).optional_input());
    info_in_ = ctx.input<msg::CameraInfo>("camera_info", "optional: the camera's intrinsics (pixels)",
                                          Qos::sensor(2).optional_input());
    composite_in_ = ctx.input<msg::Image>(
        "composite", "optional: the compositor's output (its stamp: when it was made), for the visual latency",
        Qos::reliable(4).optional_input());
    shown_in_ = ctx.input<msg::Image>("shown", "optional: the compositor's real-layer alpha (publish_shown), mono8",
                                      Qos::reliable(8).optional_input());
    device_mask_in_ =
        ctx.input<msg::Image>("true_device_mask", "optional: where the device is seen (camera_sim's), mono8",
                              Qos::reliable(8).optional_input());
    wrench_in_ = ctx.input<msg::WrenchStamped>(
        "wrench", "optional: the wrist sensor's reading, for the user's peak force while attached",
        Qos::sensor(256).optional_input());
    hand_in_ = ctx.input<msg::HandPosition>(
        "hand", "optional: the tracked hand (hand/position), for the sensor-to-setpoint latency of every hand sample",
        Qos::sensor(64).optional_input());
    measured_.contact_timing = ContactTiming(
        ctx.param<double>("force_onset", 1.0, "N: the user's force from which a contact is felt", Range{0.01, 100}));
    diagnostics_in_ = ctx.input<kernel_msgs::Diagnostics>(
        "diagnostics", "optional: the kernel's per-component diagnostics (wysiwyf/diagnostics), for loop health",
        Qos::reliable(256).optional_input());
    reports_out_ = ctx.output<msg::ContactReport>("contacts", "one report a contact", Qos::reliable(16));
    registration_out_ = ctx.output<msg::HapticRegistration>(
        "registration", "haptic registration over each attachment, when the device lets go", Qos::reliable(16));
    try {
      scene_ = haptics::load_scene(find_config_file(scene_path));
    } catch (const std::exception& e) {
      ctx.reject("scene", e.what());
    }
  }

  void activate() override {
    measured_.poses.resize_objects(scene_.models.size());
    if (!report_dir_.empty()) report_.emplace(report_dir_);
  }

  void tick(Time now) override {
    take_setpoints_and_poses(now);
    take_sensor_samples(now);
    measured_.setpoint_timing.answer_setpoints();  // after this tick's sensor samples
    take_events(now);
    take_attachments(now);
    take_camera_poses(now);
    take_images();
    measured_.measure_until(now.ns, scene_);
    while (mode_in_.take(mode_msg_)) measured_.mode = static_cast<int>(mode_msg_.mode());
    if (report_) report_->row(measured_.time_series_row(now.seconds(), scene_));
    while (diagnostics_in_.take(diagnostics_msg_)) measured_.health.add(diagnostics_msg_);
  }

  void deactivate() override {
    log(measured_.contacts.tally());
    if (measured_.haptic.attached()) detach(measured_.poses.plate().empty() ? 0 : measured_.poses.plate().back().t);
    for (const auto& line : measured_.end_lines()) log(line);
    if (!summary_path_.empty()) write_summary(summary_path_);
    if (report_) {
      write_summary(report_dir_ + "/summary.json");
      log("run report in " + report_dir_ + " (scripts/run-report " + report_dir_ + " draws its plots)");
      report_.reset();  // the CSV files closed: complete on disk
    }
  }

 private:
  // The setpoints first: a plate pose is timed against the setpoints made before it.
  void take_setpoints_and_poses(Time now) {
    while (setpoint_in_.take(setpoint_msg_)) {
      if (!msgs::all_finite(setpoint_msg_.pose())) continue;
      measured_.setpoint_timing.add_setpoint(setpoint_msg_.source().c_str(), stamp(setpoint_msg_.header(), now),
                                             msgs::to_eigen(setpoint_msg_.pose().position()),
                                             msgs::to_eigen(setpoint_msg_.twist().linear()), setpoint_msg_.sensed_ns());
    }
    while (take_checked(device_in_, device_msg_)) {
      measured_.poses.add_plate(stamp(device_msg_.header(), now), msgs::to_isometry(device_msg_.pose()));
      measured_.setpoint_timing.add_plate(measured_.poses.plate().back().t,
                                          measured_.poses.plate().back().pose.translation());
    }
    while (objects_in_.take(object_msg_)) {
      const int body = scene_.body_index(object_msg_.child_frame_id().c_str());
      if (body < 0 || !msgs::all_finite(object_msg_.pose())) continue;
      measured_.poses.add_object(static_cast<std::size_t>(body), stamp(object_msg_.header(), now),
                                 msgs::to_isometry(object_msg_.pose()));
    }
    measured_.poses.forget_before(now.ns);
  }

  // The wrist's wrench (the user's force: the reading less the tool's weight, in the sensor's
  // orientation) and the tracked hand.
  void take_sensor_samples(Time now) {
    while (wrench_in_.take(wrench_msg_)) {
      if (!msgs::all_finite(wrench_msg_.wrench())) continue;
      const std::int64_t t = stamp(wrench_msg_.header(), now);
      measured_.setpoint_timing.add_sensor_sample("wrench", t);
      if (measured_.poses.plate().empty()) continue;
      const haptics::SensorReading reading{msgs::to_eigen(wrench_msg_.wrench().force()),
                                           msgs::to_eigen(wrench_msg_.wrench().torque())};
      const double force =
          haptics::user_load(reading, measured_.poses.plate().back().pose, scene_.device, scene_.gravity).force.norm();
      measured_.haptic.force(force);
      measured_.contact_timing.add_force(t, force);
    }
    while (hand_in_.take(hand_msg_))
      if (hand_msg_.status() != msg::TRACKING_LOST)
        measured_.setpoint_timing.add_sensor_sample("hand", stamp(hand_msg_.header(), now));
  }

  void take_events(Time now) {
    while (events_in_.take(event_)) {
      const std::int64_t t = stamp(event_.header(), now);
      if (event_.kind() == msg::USER_TOUCH) {
        measured_.haptic.set_contact(event_.contact());
        measured_.contact_timing.touch(event_.contact(), event_.feature().c_str(), t);
      }
      if (event_.kind() == msg::USER_PUSH) measured_.haptic.set_push_force(event_.force());
      if (event_.kind() == msg::USER_TOUCH || event_.kind() == msg::USER_MISS) {
        const msg::ContactReport& r = measured_.contacts.measure(event_, t, scene_, measured_.poses);
        log(ContactOutcomes::line(r));
        reports_out_.write(r);
      }
    }
  }

  void take_attachments(Time now) {
    while (attach_in_.take(attach_msg_)) {
      const std::int64_t t = stamp(attach_msg_.header(), now);
      if (measured_.haptic.attached()) {
        measured_.haptic.measure_until(t, measured_.poses);
        detach(t);
      }
      if (!attach_msg_.attached()) continue;
      const int body = scene_.body_index(attach_msg_.body().c_str());
      const std::string why = body < 0 ? "an attachment to a body the scene does not have" : problem(attach_msg_);
      if (!why.empty()) {
        reject(attach_in_, why);
        continue;
      }
      measured_.haptic.attach(static_cast<std::size_t>(body), msgs::to_isometry(attach_msg_.obj_T_dev()),
                              attach_msg_.feature().c_str(), t);
    }
  }

  void detach(std::int64_t t) {
    const AttachmentRegistration::Detached d = measured_.haptic.detach(t);
    registration_out_.write(d.registration);
    log(d.line);
  }

  void take_camera_poses(Time now) {
    if (info_in_.take_latest(info_msg_)) {
      if (const auto K = msgs::intrinsics(info_msg_))
        measured_.visual.set_intrinsics({K->fx, K->fy, K->cx, K->cy});
      else
        reject(info_in_, "no focal length (expected K[0], K[4] > 0)");
    }
    while (take_checked(true_in_, pose_msg_))
      measured_.visual.add_true_pose(stamp(pose_msg_.header(), now), msgs::to_isometry(pose_msg_.pose()));
    while (take_checked(tracked_in_, pose_msg_)) {
      measured_.visual.add_tracked_pose(stamp(pose_msg_.header(), now), msgs::to_isometry(pose_msg_.pose()));
    }
  }

  // The device masks and composites first: each shown alpha is matched to them.
  void take_images() {
    while (device_mask_in_.take(image_msg_))
      if (mono8(device_mask_in_)) measured_.bleed.add_device_mask(std::move(image_msg_));  // (take() refills it)
    while (composite_in_.take(composite_msg_))
      measured_.latency.add_composite(composite_msg_.header().seq(), composite_msg_.header().stamp_ns());
    while (shown_in_.take(image_msg_)) {
      if (!mono8(shown_in_)) continue;
      measured_.latency.measure(image_msg_.header(), report_ ? &*report_ : nullptr);
      measured_.bleed.measure(image_msg_);
    }
  }

  // Whether the image just taken from `in` is mono8; if not, it is rejected there.
  bool mono8(const Input<msg::Image>& in) {
    const std::string problem = vision::image::problem(image_msg_, {"mono8"});
    if (!problem.empty()) reject(in, problem);
    return problem.empty();
  }

  void write_summary(const std::string& path) {
    std::ofstream out(path);
    out << measured_.summary_json();
    if (!out)
      warn_once("summary " + path, "could not write the summary to '" + path + "'");
    else
      log("summary: " + path);
  }

  haptics::Scene scene_;
  std::string summary_path_, report_dir_;
  std::optional<RunReport> report_;
  Measurements measured_;

  // Each input with the message its samples are taken into (reused: take() fills it in place).
  Input<msg::UserEvent> events_in_;
  msg::UserEvent event_;
  Input<msg::PoseStamped> device_in_, tracked_in_, true_in_;
  msg::PoseStamped device_msg_, pose_msg_;
  Input<msg::ObjectState> objects_in_;
  msg::ObjectState object_msg_;
  Input<msg::CartesianSetpoint> setpoint_in_;
  msg::CartesianSetpoint setpoint_msg_;
  Input<msg::WrenchStamped> wrench_in_;
  msg::WrenchStamped wrench_msg_;
  Input<msg::HandPosition> hand_in_;
  msg::HandPosition hand_msg_;
  Input<msg::Attachment> attach_in_;
  msg::Attachment attach_msg_;
  Input<msg::CameraInfo> info_in_;
  msg::CameraInfo info_msg_;
  Input<msg::Image> composite_in_, shown_in_, device_mask_in_;
  msg::Image composite_msg_, image_msg_;
  Input<msg::DisplayMode> mode_in_;
  msg::DisplayMode mode_msg_;
  Input<kernel_msgs::Diagnostics> diagnostics_in_;
  kernel_msgs::Diagnostics diagnostics_msg_;
  Output<msg::ContactReport> reports_out_;
  Output<msg::HapticRegistration> registration_out_;
};

}  // namespace wysiwyf::display

WYSIWYF_COMPONENT(wysiwyf::display::DisplayMetrics, "display_metrics")
