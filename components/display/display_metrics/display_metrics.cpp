// display_metrics: what the display promised, measured against the truth, contact by contact.
// For every touch or miss the (simulated) user reports: was it a hit, how long the plate had
// been still before the finger arrived, and how far the plate was from the pose that displays the
// feature at that moment (mm, deg; the nearest of the plate's four turns about the face normal).
// Published as ContactReports, logged one line each and summed up at the end.
//
// Haptic registration (with the supervisor's `attach`): while the device is attached to a virtual
// object, every plate pose against where the attachment holds it on the moving object
// (base_T_obj * obj_T_dev at the plate sample's stamp): p50/p99/max per attachment and over the
// run, and the largest over the attachment's first onset_window (the object starting to move
// under the push, the arm following). Published as HapticRegistration when the device lets go.
//
// Visual registration (with the tracked `eye_T_base`, the simulator's `true_eye_T_base` and
// `camera_info`): for every image, the dynamic bodies' corners drawn through the tracked camera
// pose against the true one: the largest offset in mm (camera frame) and in pixels, p50/p99/max
// over the run, logged at the end.
//
// Bleed-through (with the compositor's `shown` alpha and camera_sim's `true_device_mask`): per
// image, the pixels of the real device that the user sees (shown alpha > 127 where the device,
// not the hand, is in front); the user should see only the virtual scene and the hand.
//
// Contact timing (with `wrench`, `shown` and `composite`): per touch, when the force rose and when
// the user first saw the finger there (the first composite of a camera frame taken at or after
// the touch): ms and frames.
//
// Loop health (with the kernel's `diagnostics`): per component, its configured and achieved
// rate, the worst tick p99 and max over the windows, overruns, dropped and rejected samples,
// warnings; in the summary.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <deque>
#include <limits>
#include <map>
#include <optional>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "image/image_view.hpp"
#include "registration_stats.hpp"
#include "following_lag.hpp"
#include "sensor_to_setpoint.hpp"
#include "run_report.hpp"

#include "scene/scene.hpp"
#include "scene/tool_load.hpp"
#include "wysiwyf/camera_info.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::display {

namespace {

using Vec3 = Eigen::Vector3d;

struct Sample {
  std::int64_t t = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

}  // namespace

class DisplayMetrics final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("measures each contact: hit or miss, plate still before the finger, plate offset from the feature");
    scene_path_ = ctx.param<std::string>("scene", "scenes/display_demo.yaml", "scene file with its features");
    still_speed_ = ctx.param<double>("still_speed", 0.002, "m/s: the plate slower than this is still", Range{1e-5, 1});
    history_ns_ = static_cast<std::int64_t>(
        ctx.param<double>("history", 10.0, "s of plate and object poses kept (events may come late)", Range{1, 600}) *
        1e9);
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
    lag_ = FollowingLag(ctx.param<double>("lag_min_speed", 0.02,
                                          "m/s: setpoints commanding motion at least this fast are timed to the plate",
                                          Range{1e-4, 10}),
                        500'000'000);
    mode_in_ = ctx.input<msg::DisplayMode>("mode", "optional: the display's mode (the supervisor's), for the report",
                                           Qos::reliable(16).optional_input());
    onset_window_ns_ = static_cast<std::int64_t>(
        ctx.param<double>("onset_window", 0.1, "s after attaching counted as the push's onset", Range{0.001, 10}) *
        1e9);
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
    force_onset_ =
        ctx.param<double>("force_onset", 1.0, "N: the user's force from which a contact is felt", Range{0.01, 100});
    diagnostics_in_ = ctx.input<kernel_msgs::Diagnostics>(
        "diagnostics", "optional: the kernel's per-component diagnostics (wysiwyf/diagnostics), for loop health",
        Qos::reliable(256).optional_input());
    reports_out_ = ctx.output<msg::ContactReport>("contacts", "one report a contact", Qos::reliable(16));
    registration_out_ = ctx.output<msg::HapticRegistration>(
        "registration", "haptic registration over each attachment, when the device lets go", Qos::reliable(16));
    try {
      scene_ = haptics::load_scene(find_config_file(scene_path_));
    } catch (const std::exception& e) {
      ctx.reject("scene", e.what());
    }
  }

  void tick(Time now) override {
    while (setpoint_in_.take(setpoint_msg_)) {  // first: a plate pose is timed against the setpoints before it
      if (!msgs::all_finite(setpoint_msg_.pose())) continue;
      const std::int64_t t = stamp(setpoint_msg_.header(), now);
      lag_.setpoint(t, msgs::to_eigen(setpoint_msg_.pose().position()), msgs::to_eigen(setpoint_msg_.twist().linear()));
      answers_.push_back(
          {setpoint_msg_.source().c_str(), t, setpoint_msg_.sensed_ns()});  // timed once the samples are in
    }
    while (device_in_.take(device_msg_)) {
      if (!msgs::all_finite(device_msg_.pose())) {
        reject(device_in_, "a non-finite pose");
        continue;
      }
      plate_.push_back({stamp(device_msg_.header(), now), msgs::to_isometry(device_msg_.pose())});
      lag_.plate(plate_.back().t, plate_.back().pose.translation());
    }
    while (objects_in_.take(object_msg_)) {
      const int body = scene_.body_index(object_msg_.child_frame_id().c_str());
      if (body < 0 || !msgs::all_finite(object_msg_.pose())) continue;
      objects_[static_cast<std::size_t>(body)].push_back(
          {stamp(object_msg_.header(), now), msgs::to_isometry(object_msg_.pose())});
    }
    while (!plate_.empty() && plate_.front().t < now.ns - history_ns_) plate_.pop_front();
    for (auto& h : objects_)
      while (h.size() > 1 && h[1].t < now.ns - history_ns_) h.pop_front();
    while (wrench_in_.take(wrench_msg_)) {
      if (!msgs::all_finite(wrench_msg_.wrench())) continue;
      const std::int64_t t = stamp(wrench_msg_.header(), now);
      sensed_.sample("wrench", t);
      if (plate_.empty()) continue;
      // The user's force: the reading less the tool's weight, in the sensor's orientation.
      const haptics::SensorReading reading{msgs::to_eigen(wrench_msg_.wrench().force()),
                                           msgs::to_eigen(wrench_msg_.wrench().torque())};
      const double force = haptics::user_load(reading, plate_.back().pose, scene_.device, scene_.gravity).force.norm();
      if (attachment_) attachment_->peak_force = std::max(attachment_->peak_force, force);
      forces_.emplace_back(t, force);
    }
    while (hand_in_.take(hand_msg_))
      if (hand_msg_.status() != msg::TRACKING_LOST) sensed_.sample("hand", stamp(hand_msg_.header(), now));
    for (const auto& a : answers_) sensed_.setpoint(a.source, a.stamp, a.sensed);
    answers_.clear();
    while (events_in_.take(event_)) {
      if (event_.kind() == msg::USER_TOUCH) {
        contact_ = event_.contact();
        timings_.push_back({event_.contact(), event_.feature().c_str(), stamp(event_.header(), now)});
      }
      if (event_.kind() == msg::USER_PUSH) push_force_ = event_.force();
      if (event_.kind() == msg::USER_TOUCH || event_.kind() == msg::USER_MISS) measure(now);
    }
    while (attach_in_.take(attach_msg_)) {
      const std::int64_t t = stamp(attach_msg_.header(), now);
      if (attachment_) {
        register_until(t);
        finish_attachment(t);
      }
      if (attach_msg_.attached()) start_attachment(t);
    }
    if (attachment_) register_until(now.ns);
    measure_visual(now);
    measure_bleed();
    time_contacts();
    while (!forces_.empty() && forces_.front().first < now.ns - history_ns_) forces_.pop_front();
    while (!frames_.empty() && frames_.front().first < now.ns - history_ns_) frames_.pop_front();
    while (mode_in_.take(mode_msg_)) mode_ = static_cast<int>(mode_msg_.mode());
    if (report_) report_row(now);
    while (diagnostics_in_.take(diagnostics_msg_)) {
      Health& c = health_[diagnostics_msg_.instance().c_str()];
      c.type = diagnostics_msg_.type().c_str();
      c.rate_hz = diagnostics_msg_.rate_hz();
      c.tick_rate_hz = diagnostics_msg_.tick_rate_hz();
      c.tick_p99_us = std::max(c.tick_p99_us, diagnostics_msg_.tick_time_p99_us());
      c.tick_max_us = std::max(c.tick_max_us, diagnostics_msg_.tick_time_max_us());
      c.ticks = diagnostics_msg_.ticks(), c.overruns = diagnostics_msg_.overruns();
      c.dropped = diagnostics_msg_.dropped_samples(), c.rejected = diagnostics_msg_.rejected_samples();
      c.warnings = diagnostics_msg_.warnings();
    }
  }

  void activate() override {
    objects_.resize(scene_.models.size());
    if (!report_dir_.empty()) report_.emplace(report_dir_);
  }

  void deactivate() override {
    int hits = 0;
    for (const auto& r : reports_) hits += r.hit() ? 1 : 0;
    log(std::to_string(reports_.size()) + " contact(s), " + std::to_string(hits) + " hit(s)");
    if (attachment_) finish_attachment(plate_.empty() ? 0 : plate_.back().t);
    if (visual_mm_.samples() > 0)
      log("visual registration (the moving bodies' corners, tracked against true camera pose) over " +
          std::to_string(visual_mm_.samples()) + " images: p50 " + std::to_string(visual_mm_.percentile(50)) +
          " mm / " + std::to_string(visual_px_.percentile(50)) + " px, p99 " +
          std::to_string(visual_mm_.percentile(99)) + " mm / " + std::to_string(visual_px_.percentile(99)) +
          " px, max " + std::to_string(visual_mm_.max()) + " mm / " + std::to_string(visual_px_.max()) + " px");
    for (const auto& c : timings_)
      if (c.done)
        log("contact " + std::to_string(c.contact) + " timing: the force rose " +
            std::to_string(static_cast<double>(c.force_at - c.touch) * 1e-6) + " ms after the touch, the user saw it " +
            std::to_string(static_cast<double>(c.seen_at - c.touch) * 1e-6) + " ms after it");
    if (latency_ms_.samples() > 0)
      log("visual latency, camera frame to composite (sim time): p50 " + std::to_string(latency_ms_.percentile(50)) +
          " ms, max " + std::to_string(latency_ms_.max()) + " ms over " + std::to_string(latency_ms_.samples()) +
          " images");
    if (bleed_px_.samples() > 0)
      log("bleed-through (real device pixels the user sees) over " + std::to_string(bleed_px_.samples()) +
          " images: " + std::to_string(bleed_frames_) + " with any, p99 " + std::to_string(bleed_px_.percentile(99)) +
          " px, max " + std::to_string(bleed_px_.max()) + " px");
    if (lag_.lag_ms().samples() > 0)
      log("setpoint to motion: the plate reaches a moving setpoint p50 " +
          std::to_string(lag_.lag_ms().percentile(50)) + " ms, p99 " + std::to_string(lag_.lag_ms().percentile(99)) +
          " ms after it was made (" + std::to_string(lag_.lag_ms().samples()) + " setpoints; " +
          std::to_string(lag_.not_reached()) + " not reached)");
    for (const auto& [sensor, ms] : sensed_.by_sensor())
      log("sensor sample to setpoint (" + sensor + "): p50 " + std::to_string(ms.percentile(50)) + " ms, p99 " +
          std::to_string(ms.percentile(99)) + " ms, max " + std::to_string(ms.max()) + " ms over " +
          std::to_string(ms.samples()) + " samples");
    if (run_.mm.samples() > 0)
      log("haptic registration while attached, the whole run: p50 " + std::to_string(run_.mm.percentile(50)) +
          " mm, p99 " + std::to_string(run_.mm.percentile(99)) + " mm, max " + std::to_string(run_.mm.max()) +
          " mm / " + std::to_string(run_.deg.max()) + " deg over " + std::to_string(run_.mm.samples()) + " samples");
    if (!summary_path_.empty()) write_summary(summary_path_);
    if (report_) {
      write_summary(report_dir_ + "/summary.json");
      log("run report in " + report_dir_ + " (scripts/run-report " + report_dir_ + " draws its plots)");
      report_.reset();  // the CSV files closed: complete on disk
    }
  }

 private:
  static std::int64_t stamp(const std_msgs::Header& h, Time now) { return h.stamp_ns() ? h.stamp_ns() : now.ns; }

  // The newest sample at or before t (the oldest if none is).
  static const Sample* at(const std::deque<Sample>& h, std::int64_t t) {
    if (h.empty()) return nullptr;
    const auto after = std::upper_bound(h.begin(), h.end(), t, [](std::int64_t v, const Sample& s) { return v < s.t; });
    return after == h.begin() ? &h.front() : &*(after - 1);
  }

  void measure(Time now) {
    const std::int64_t t = event_.header().stamp_ns() ? event_.header().stamp_ns() : now.ns;
    msg::ContactReport r;
    fill_header(r.header(), t, reports_.size(), "base");
    r.contact(event_.contact());
    r.feature(event_.feature());
    r.hit(event_.kind() == msg::USER_TOUCH);
    r.still_before_s(-1);
    r.offset_mm(-1);
    r.angle_deg(-1);
    const haptics::DisplayFeature* f = scene_.feature(event_.feature().c_str());
    const Sample* plate = at(plate_, t);
    if (f && plate && !objects_[static_cast<std::size_t>(f->body)].empty()) {
      // Still since: walking back from the arrival, the last 100 ms window the plate moved in (over a
      // shorter one the encoders' quantisation, 0.06 mm a step, reads as motion).
      std::int64_t still_since = plate_.front().t;
      for (auto it = plate_.rbegin(); it != plate_.rend(); ++it) {
        if (it->t > t) continue;
        const Sample* before = at(plate_, it->t - 100'000'000);
        if (before && it->t > before->t &&
            (it->pose.translation() - before->pose.translation()).norm() / ((it->t - before->t) * 1e-9) >
                still_speed_) {
          still_since = it->t;
          break;
        }
      }
      r.still_before_s(static_cast<double>(t - still_since) * 1e-9);
      const Eigen::Isometry3d base_T_obj = at(objects_[static_cast<std::size_t>(f->body)], t)->pose;
      double best_angle = std::numeric_limits<double>::infinity(), offset = 0;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Isometry3d want = base_T_obj * f->obj_T_plate * Eigen::AngleAxisd(k * M_PI / 2, Vec3::UnitZ());
        const double angle =
            Eigen::Quaterniond(want.linear()).angularDistance(Eigen::Quaterniond(plate->pose.linear()));
        if (angle < best_angle) best_angle = angle, offset = (want.translation() - plate->pose.translation()).norm();
      }
      r.offset_mm(offset * 1e3);
      r.angle_deg(best_angle * 180 / M_PI);
    }
    log("contact " + std::to_string(r.contact()) + " (" + r.feature().c_str() + "): " + (r.hit() ? "hit" : "MISS") +
        ", plate still " + std::to_string(static_cast<int>(r.still_before_s() * 1e3)) + " ms before the finger, " +
        std::to_string(r.offset_mm()) + " mm / " + std::to_string(r.angle_deg()) + " deg from the feature");
    reports_out_.write(r);
    reports_.push_back(r);
  }

  // Each tracked pose against the true pose of the same image (equal stamps).
  void measure_visual(Time now) {
    if (info_in_.take_latest(info_msg_)) {
      if (const auto K = msgs::intrinsics(info_msg_))
        K_ = {K->fx, K->fy, K->cx, K->cy};
      else
        reject(info_in_, "no focal length (expected K[0], K[4] > 0)");
    }
    while (true_in_.take(pose_msg_))
      if (msgs::all_finite(pose_msg_.pose()))
        true_poses_.push_back({stamp(pose_msg_.header(), now), msgs::to_isometry(pose_msg_.pose())});
    while (true_poses_.size() > 64) true_poses_.pop_front();
    while (tracked_in_.take(pose_msg_)) {
      if (!msgs::all_finite(pose_msg_.pose())) {
        reject(tracked_in_, "a non-finite pose");
        continue;
      }
      tracked_.push_back({stamp(pose_msg_.header(), now), msgs::to_isometry(pose_msg_.pose())});
    }
    // No pixels without intrinsics; no truth on real hardware: nothing to keep.
    while (!tracked_.empty() && (!(K_[0] > 0) || tracked_.size() > 64)) tracked_.pop_front();
    while (!tracked_.empty()) {
      const Sample& drawn = tracked_.front();
      const auto truth =
          std::find_if(true_poses_.begin(), true_poses_.end(), [&](const Sample& s) { return s.t == drawn.t; });
      if (truth == true_poses_.end()) {
        if (true_poses_.empty() || true_poses_.back().t <= drawn.t) break;  // may still come
        tracked_.pop_front();                                               // never coming
        continue;
      }
      corners_.clear();
      for (std::size_t b = 0; b < scene_.models.size(); ++b) {
        if (!scene_.models[b].dynamic || objects_[b].empty()) continue;
        const Eigen::Isometry3d base_T_obj = at(objects_[b], drawn.t)->pose;
        const Vec3 h = scene_.models[b].half_extents;
        for (int c = 0; c < 8; ++c)
          corners_.push_back(base_T_obj * Vec3(c & 1 ? h.x() : -h.x(), c & 2 ? h.y() : -h.y(), c & 4 ? h.z() : -h.z()));
      }
      if (!corners_.empty()) {
        const VisualError e = visual_error(drawn.pose, truth->pose, corners_, K_);
        visual_mm_.add(e.mm, drawn.t);
        last_visual_mm_ = e.mm;
        visual_px_.add(e.px, drawn.t);
      }
      tracked_.pop_front();
    }
  }

  static std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    std::ostringstream o;
    o.precision(9);
    o << v;
    return o.str();
  }
  // One figure's "<prefix>p50_<unit>", "<prefix>p99_<unit>" and "<prefix>max_<unit>" members.
  static std::string figures(const Percentiles& p, const std::string& unit, const std::string& prefix = "") {
    return "\"" + prefix + "p50_" + unit + "\": " + number(p.percentile(50)) + ", \"" + prefix + "p99_" + unit +
           "\": " + number(p.percentile(99)) + ", \"" + prefix + "max_" + unit + "\": " + number(p.max());
  }
  static std::string quoted(const std::string& text) {
    std::string q = "\"";
    for (char c : text) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    return q + "\"";
  }

  // The latest of each signal, one row a tick.
  void report_row(Time now) {
    TimeSeriesRow r;
    r.t_s = now.seconds();
    if (!forces_.empty()) r.force_n = forces_.back().second;
    if (!plate_.empty()) r.plate = plate_.back().pose.translation();
    for (std::size_t b = 0; b < scene_.models.size(); ++b)
      if (scene_.models[b].dynamic && !objects_[b].empty()) {
        r.cube = objects_[b].back().pose.translation();
        break;
      }
    r.mode = mode_;
    r.attached = attachment_.has_value();
    if (attachment_) r.haptic_mm = last_haptic_mm_;
    r.visual_mm = last_visual_mm_;
    report_->row(r);
  }

  // Every figure of the run, units in the keys: the run report's summary.json.
  void write_summary(const std::string& path) {
    std::ostringstream j;
    j << "{\n  \"contacts\": [";
    for (std::size_t i = 0; i < reports_.size(); ++i) {
      const auto& r = reports_[i];
      j << (i ? "," : "") << "\n    {\"contact\": " << r.contact() << ", \"feature\": " << quoted(r.feature().c_str())
        << ", \"hit\": " << (r.hit() ? "true" : "false")
        << ", \"still_before_ms\": " << number(r.still_before_s() * 1e3) << ", \"offset_mm\": " << number(r.offset_mm())
        << ", \"angle_deg\": " << number(r.angle_deg()) << "}";
    }
    j << "\n  ],\n  \"haptic_registration\": {\n    \"attachments\": [";
    for (std::size_t i = 0; i < registrations_.size(); ++i) {
      const auto& r = registrations_[i];
      j << (i ? "," : "") << "\n      {\"contact\": " << r.contact() << ", \"feature\": " << quoted(r.feature().c_str())
        << ", \"samples\": " << r.samples() << ", \"p50_mm\": " << number(r.p50_mm())
        << ", \"p99_mm\": " << number(r.p99_mm()) << ", \"max_mm\": " << number(r.max_mm())
        << ", \"max_deg\": " << number(r.max_deg()) << ", \"onset_max_mm\": " << number(r.onset_max_mm())
        << ", \"onset_max_deg\": " << number(r.onset_max_deg()) << ", \"peak_force_n\": " << number(r.peak_force_n())
        << ", \"push_force_n\": " << number(r.push_force_n()) << ", \"overshoot_mm\": " << number(r.overshoot_mm())
        << "}";
    }
    double overshoot = 0;
    for (const auto& r : registrations_) overshoot = std::max(overshoot, r.overshoot_mm());
    j << "\n    ],\n    \"run\": {\"samples\": " << run_.mm.samples() << ", " << figures(run_.mm, "mm")
      << ", \"max_deg\": " << number(run_.deg.max()) << ", \"overshoot_mm\": " << number(overshoot) << "}\n  },\n";
    j << "  \"visual_registration\": {\"images\": " << visual_mm_.samples() << ", " << figures(visual_mm_, "mm") << ", "
      << figures(visual_px_, "px") << "},\n";
    j << "  \"bleed_through\": {\"images\": " << bleed_px_.samples() << ", \"images_with_any\": " << bleed_frames_
      << ", \"p99_px\": " << number(bleed_px_.percentile(99)) << ", \"max_px\": " << number(bleed_px_.max())
      << "},\n  \"setpoint_to_motion\": {\"setpoints\": " << lag_.lag_ms().samples()
      << ", \"not_reached\": " << lag_.not_reached() << ", " << figures(lag_.lag_ms(), "ms")
      << "},\n  \"sensor_to_setpoint\": {";
    bool first_source = true;
    for (const auto& [sensor, ms] : sensed_.by_sensor()) {
      j << (first_source ? "" : ",") << "\n    " << quoted(sensor) << ": {\"samples\": " << ms.samples() << ", "
        << figures(ms, "ms") << "}";
      first_source = false;
    }
    j << (first_source ? "" : "\n  ") << "},\n  \"visual_latency\": {\"images\": " << latency_ms_.samples() << ", "
      << figures(latency_ms_, "ms", "camera_to_composite_") << "},\n  \"contact_timing\": [";
    bool first_timing = true;
    for (const auto& c : timings_) {
      if (!c.done) continue;
      const double ms = static_cast<double>(c.seen_at - c.force_at) * 1e-6;
      j << (first_timing ? "" : ",") << "\n    {\"contact\": " << c.contact << ", \"feature\": " << quoted(c.feature)
        << ", \"force_rise_after_touch_ms\": " << number(static_cast<double>(c.force_at - c.touch) * 1e-6)
        << ", \"seen_after_touch_ms\": " << number(static_cast<double>(c.seen_at - c.touch) * 1e-6)
        << ", \"seen_after_force_ms\": " << number(ms) << ", \"seen_after_force_frames\": "
        << number(c.frame_period > 0 ? ms * 1e6 / static_cast<double>(c.frame_period) : -1) << "}";
      first_timing = false;
    }
    j << (first_timing ? "" : "\n  ") << "],\n  \"loop_health\": {";
    bool first = true;
    for (const auto& [name, c] : health_) {
      j << (first ? "" : ",") << "\n    " << quoted(name) << ": {\"type\": " << quoted(c.type)
        << ", \"rate_hz\": " << number(c.rate_hz) << ", \"achieved_hz\": " << number(c.tick_rate_hz)
        << ", \"tick_p99_us\": " << number(c.tick_p99_us) << ", \"tick_max_us\": " << number(c.tick_max_us)
        << ", \"ticks\": " << c.ticks << ", \"overruns\": " << c.overruns << ", \"dropped\": " << c.dropped
        << ", \"rejected\": " << c.rejected << ", \"warnings\": " << c.warnings << "}";
      first = false;
    }
    j << (health_.empty() ? "" : "\n  ") << "}\n}\n";
    std::ofstream out(path);
    out << j.str();
    if (!out)
      warn_once("summary " + path, "could not write the summary to '" + path + "'");
    else
      log("summary: " + path);
  }

  // Contact timing: for each touch, when the wrist force rose past force_onset (from 0.1 s before
  // the touch) and when the user first saw it: the first composite of a camera frame taken at or
  // after the touch. Positive: the eye learns later than the hand.
  void time_contacts() {
    for (auto& c : timings_) {
      if (c.done) continue;
      if (c.force_at < 0) {
        // Only the samples not looked at yet (the stamps rise).
        const std::int64_t from = std::max(c.touch - 100'000'000, c.forces_seen_until + 1);
        auto it = std::lower_bound(forces_.begin(), forces_.end(), from,
                                   [](const auto& sample, std::int64_t t) { return sample.first < t; });
        for (; it != forces_.end(); ++it) {
          c.forces_seen_until = it->first;
          if (it->second > force_onset_) {
            c.force_at = it->first;
            break;
          }
        }
      }
      if (c.seen_at < 0)
        for (const auto& [taken, made] : frames_)
          if (taken >= c.touch) {
            c.seen_at = made, c.frame_period = frame_period();
            break;
          }
      c.done = c.force_at >= 0 && c.seen_at >= 0;
    }
  }
  std::int64_t frame_period() const {
    return frames_.size() > 1 ? frames_.back().first - frames_[frames_.size() - 2].first : 0;
  }

  // Each shown alpha against the device mask of the same camera frame (equal stamps).
  void measure_bleed() {
    while (device_mask_in_.take(image_msg_)) {
      if (!image::problem(image_msg_, {"mono8"}).empty()) {
        reject(device_mask_in_, image::problem(image_msg_, {"mono8"}));
        continue;
      }
      device_masks_.push_back(std::move(image_msg_));  // (take() refills it)
      if (device_masks_.size() > 8) device_masks_.pop_front();
    }
    // Composites by seq: when each was made, for the latency from its camera frame (the shown's stamp).
    while (composite_in_.take(composite_msg_)) {
      made_at_.emplace_back(composite_msg_.header().seq(), composite_msg_.header().stamp_ns());
      if (made_at_.size() > 16) made_at_.pop_front();
    }
    while (shown_in_.take(image_msg_)) {
      if (!image::problem(image_msg_, {"mono8"}).empty()) {
        reject(shown_in_, image::problem(image_msg_, {"mono8"}));
        continue;
      }
      for (const auto& [seq, made] : made_at_) {
        const std::int64_t frame = image_msg_.header().stamp_ns();
        if (seq != image_msg_.header().seq() || made < frame) continue;
        frames_.emplace_back(frame, made);
        latency_ms_.add(static_cast<double>(made - frame) * 1e-6, frame);
        if (report_) report_->latency(static_cast<double>(made) * 1e-9, static_cast<double>(made - frame) * 1e-6);
      }
      const auto mask = std::find_if(device_masks_.begin(), device_masks_.end(), [&](const msg::Image& m) {
        return m.header().stamp_ns() == image_msg_.header().stamp_ns();
      });
      if (mask == device_masks_.end() || mask->width() != image_msg_.width() || mask->height() != image_msg_.height())
        continue;  // its frame's truth is gone or never came
      // The device's own pixels, not its outline: at an edge the image's blur and the keyer's soft
      // matte mix it with what is next to it (the hand over it, the cloth around it).
      cv::erode(image::view(*mask), inner_, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
      cv::Mat seen = image::view(image_msg_) > 127;
      seen &= inner_;
      const int bleed = cv::countNonZero(seen);
      bleed_px_.add(bleed, image_msg_.header().stamp_ns());
      bleed_frames_ += bleed > 0 ? 1 : 0;
    }
  }

  struct Attachment {
    std::size_t body = 0;
    Eigen::Isometry3d obj_T_dev = Eigen::Isometry3d::Identity();
    std::string feature;
    std::int64_t since = 0, measured_until = 0;
    RegistrationStats all, onset;
    double peak_force = -1;  // N, the user's largest force while attached (-1: no wrench)
    double overshoot = 0;    // m, the plate's deepest past the held face (along its normal, into the object)
  };

  void start_attachment(std::int64_t t) {
    const int body = scene_.body_index(attach_msg_.body().c_str());
    if (body < 0 || !msgs::all_finite(attach_msg_.obj_T_dev())) {
      reject(attach_in_, "an attachment to a body the scene does not have, or a non-finite obj_T_dev");
      return;
    }
    attachment_.emplace();
    attachment_->body = static_cast<std::size_t>(body);
    attachment_->obj_T_dev = msgs::to_isometry(attach_msg_.obj_T_dev());
    attachment_->feature = attach_msg_.feature().c_str();
    attachment_->since = t;
    attachment_->measured_until = t - 1;
  }

  // Every plate sample since the last one measured, up to t and to the newest object pose.
  void register_until(std::int64_t t) {
    Attachment& a = *attachment_;
    const auto& object = objects_[a.body];
    if (object.empty()) return;
    t = std::min(t, object.back().t);
    const std::int64_t from = std::max(a.measured_until, a.since - 1);
    for (auto it = std::upper_bound(plate_.begin(), plate_.end(), from,
                                    [](std::int64_t v, const Sample&s) { return v < s.t; });
         it != plate_.end() && it->t <= t; ++it) {
      const Sample& s = *it;
      const Eigen::Isometry3d want = at(object, s.t)->pose * a.obj_T_dev;
      const RegistrationError e = registration_error(want, s.pose);
      a.overshoot = std::max(a.overshoot, -(want.inverse() * s.pose.translation()).z());  // (z: out of the face)
      last_haptic_mm_ = e.mm;
      a.all.add(e, s.t);
      run_.add(e, s.t);
      if (s.t - a.since <= onset_window_ns_) a.onset.add(e, s.t);
      a.measured_until = s.t;
    }
  }

  void finish_attachment(std::int64_t t) {
    const Attachment& a = *attachment_;
    msg::HapticRegistration r;
    fill_header(r.header(), t, registration_seq_++, "base");
    r.contact(contact_);
    r.feature(a.feature);
    r.samples(static_cast<std::uint32_t>(a.all.mm.samples()));
    r.p50_mm(a.all.mm.percentile(50));
    r.p99_mm(a.all.mm.percentile(99));
    r.max_mm(a.all.mm.max());
    r.max_deg(a.all.deg.max());
    r.onset_max_mm(a.onset.mm.max());
    r.onset_max_deg(a.onset.deg.max());
    r.peak_force_n(a.peak_force);
    r.push_force_n(push_force_);
    r.overshoot_mm(a.overshoot * 1e3);
    registration_out_.write(r);
    registrations_.push_back(r);
    log("contact " + std::to_string(contact_) + " (" + a.feature + ") attached " +
        std::to_string(static_cast<double>(t - a.since) * 1e-9) + " s: plate from the held feature p50 " +
        std::to_string(r.p50_mm()) + " mm, p99 " + std::to_string(r.p99_mm()) + " mm, max " +
        std::to_string(r.max_mm()) + " mm (at " + std::to_string(static_cast<double>(a.all.mm.max_at()) * 1e-9) +
        " s) / " + std::to_string(r.max_deg()) + " deg; onset max " + std::to_string(r.onset_max_mm()) + " mm / " +
        std::to_string(r.onset_max_deg()) + " deg; peak force " + std::to_string(r.peak_force_n()) + " N (push " +
        std::to_string(r.push_force_n()) + " N); deepest past the face " + std::to_string(r.overshoot_mm()) + " mm");
    attachment_.reset();
  }

  std::string scene_path_;
  haptics::Scene scene_;
  std::int64_t onset_window_ns_ = 0;
  std::optional<Attachment> attachment_;
  RegistrationStats run_;
  std::uint32_t contact_ = 0;
  double push_force_ = -1;  // N, the user's last push target (user_sim's PUSH event)
  msg::WrenchStamped wrench_msg_;
  Input<msg::WrenchStamped> wrench_in_;
  std::uint64_t registration_seq_ = 0;
  // One component's health, from the kernel's diagnostics (the latest; worst tick figures).
  struct Health {
    std::string type;
    double rate_hz = 0, tick_rate_hz = 0, tick_p99_us = 0, tick_max_us = 0;
    std::uint64_t ticks = 0, overruns = 0, dropped = 0, rejected = 0, warnings = 0;
  };
  std::map<std::string, Health> health_;
  kernel_msgs::Diagnostics diagnostics_msg_;
  Input<kernel_msgs::Diagnostics> diagnostics_in_;
  std::string summary_path_, report_dir_;
  FollowingLag lag_{0.02, 500'000'000};  // made in configure with lag_min_speed
  SensorToSetpoint sensed_;
  struct Answer {
    std::string source;
    std::int64_t stamp, sensed;
  };
  std::vector<Answer> answers_;  // this tick's setpoints, timed after its sensor samples
  msg::HandPosition hand_msg_;
  Input<msg::HandPosition> hand_in_;
  msg::CartesianSetpoint setpoint_msg_;
  Input<msg::CartesianSetpoint> setpoint_in_;
  std::optional<RunReport> report_;
  std::optional<double> last_haptic_mm_, last_visual_mm_;
  int mode_ = -1;
  msg::DisplayMode mode_msg_;
  Input<msg::DisplayMode> mode_in_;
  std::deque<msg::Image> device_masks_;
  std::deque<std::pair<std::uint64_t, std::int64_t>> made_at_;  // composite seq, its stamp
  std::deque<std::pair<std::int64_t, std::int64_t>> frames_;    // camera stamp, when its composite was made
  std::deque<std::pair<std::int64_t, double>> forces_;          // the user's force, N, by stamp
  struct ContactTiming {
    std::uint32_t contact = 0;
    std::string feature;
    std::int64_t touch = 0, force_at = -1, seen_at = -1, frame_period = 0;
    std::int64_t forces_seen_until = -1;  // the newest force sample looked at
    bool done = false;
  };
  std::vector<ContactTiming> timings_;
  double force_onset_ = 1.0;
  Percentiles latency_ms_;
  msg::Image composite_msg_;
  Input<msg::Image> composite_in_;
  cv::Mat inner_;
  msg::Image image_msg_;
  Percentiles bleed_px_;
  std::size_t bleed_frames_ = 0;
  Input<msg::Image> shown_in_, device_mask_in_;
  std::vector<msg::HapticRegistration> registrations_;
  std::deque<Sample> tracked_, true_poses_;
  std::array<double, 4> K_{};
  std::vector<Vec3> corners_;
  Percentiles visual_mm_, visual_px_;
  msg::PoseStamped pose_msg_;
  msg::CameraInfo info_msg_;
  Input<msg::PoseStamped> tracked_in_, true_in_;
  Input<msg::CameraInfo> info_in_;
  msg::Attachment attach_msg_;
  Input<msg::Attachment> attach_in_;
  Output<msg::HapticRegistration> registration_out_;
  double still_speed_ = 0.002;
  std::int64_t history_ns_ = 0;
  std::deque<Sample> plate_;
  std::vector<std::deque<Sample>> objects_;
  std::vector<msg::ContactReport> reports_;
  msg::UserEvent event_;
  msg::PoseStamped device_msg_;
  msg::ObjectState object_msg_;
  Input<msg::UserEvent> events_in_;
  Input<msg::PoseStamped> device_in_;
  Input<msg::ObjectState> objects_in_;
  Output<msg::ContactReport> reports_out_;
};

}  // namespace wysiwyf::display

WYSIWYF_COMPONENT(wysiwyf::display::DisplayMetrics, "display_metrics")
