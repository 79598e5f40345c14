// supervisor: the modes, contact, the setpoint sent (supervisor.hpp says how it works).
#include "supervisor.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::display {

void Supervisor::configure(Context& ctx) {
  ctx.summary("the display's modes (idle, surface, admittance, fault) and the only writer of the robot setpoint");
  scene_path_ = ctx.param<std::string>("scene", "scenes/cube_against_wall.yaml", "scene file (tool, features)");
  ContactThresholds t;
  t.contact_force = ctx.param<double>("contact_force", 2.0, "N: the user's force that starts a touch", Range{0.1, 100});
  t.contact_dwell = ctx.param<double>("contact_dwell", 0.02, "s it must last", Range{0, 1});
  t.release_force = ctx.param<double>("release_force", 1.0, "N: below this the touch may end", Range{0, 100});
  t.release_dwell = ctx.param<double>("release_dwell", 0.1, "s it must last", Range{0, 5});
  t.contact_distance =
      ctx.param<double>("contact_distance", 0.05, "m: a touch needs a tracked hand this near the plate", Range{0, 1});
  t.release_distance = ctx.param<double>(
      "release_distance", 0.02, "m: a release needs a tracked hand at least this far from the plate", Range{0, 1});
  if (!(t.release_force < t.contact_force)) ctx.reject("release_force", "must be below contact_force");
  detector_ = ContactDetector(t);
  finger_radius_ = ctx.param<double>("finger_radius", 0.01, "m around the tracked hand point", Range{0, 0.1});
  max_switch_step_ = ctx.param<double>(
      "max_switch_step", 1e-4, "m: a new source takes over only within this of the last setpoint", Range{1e-6, 0.1});
  switch_timeout_ns_ =
      nanos(ctx.param<double>("switch_timeout", 0.1, "s a new source has to take over", Range{0.001, 10}));
  max_speed_ =
      ctx.param<double>("max_setpoint_speed", 2.0, "m/s: a setpoint moving faster is a fault", Range{0.01, 100});
  setpoint_timeout_ns_ = nanos(ctx.param<double>(
      "setpoint_timeout", 0.03, "s without a setpoint from the mode's source: a fault", Range{0.001, 10}));
  wrench_timeout_ns_ =
      nanos(ctx.param<double>("wrench_timeout", 0.03, "s without a wrist reading: a fault", Range{0.001, 10}));
  status_timeout_ns_ = nanos(ctx.param<double>(
      "status_timeout", 0.5, "s without the arm's or the planner's status: a fault", Range{0.01, 60}));
  auto_recover_ = ctx.param<bool>("auto_recover", true, "leave a fault once every input is good again");
  recover_after_ns_ = nanos(ctx.param<double>("recover_after", 0.5, "s of good input before that", Range{0, 60}));

  surface_in_ = ctx.input<msg::CartesianSetpoint>("surface", "the surface planner's setpoints", Qos::reliable(32));
  admittance_in_ = ctx.input<msg::CartesianSetpoint>("admittance", "admittance_sim's setpoints", Qos::reliable(32));
  wrench_in_ = ctx.input<msg::WrenchStamped>("wrench", "the wrist F/T sensor (sensor frame, tool weight included)",
                                             Qos::sensor(16));
  device_in_ = ctx.input<msg::PoseStamped>("device_pose", "the plate's measured pose base_T_dev", Qos::sensor(4));
  hand_in_ = ctx.input<msg::HandPosition>("hand", "the tracked fingertip (cross-check)", Qos::sensor(8));
  robot_in_ = ctx.input<msg::RobotStatus>("robot_status", "the arm's safety state", Qos::reliable(8));
  planner_in_ = ctx.input<msg::PlannerStatus>("planner_status", "the surface planner's target", Qos::reliable(8));
  objects_in_ = ctx.input<msg::ObjectState>("objects", "the virtual objects (for the attachment)", Qos::reliable(64));
  setpoint_out_ = ctx.output<msg::CartesianSetpoint>("setpoint", "the robot's setpoint: the one writer",
                                                     Qos::reliable().one_writer());
  mode_out_ = ctx.output<msg::DisplayMode>("mode", "the display's mode and why",
                                           Qos{Reliability::kReliable, Durability::kTransientLocal, 8, 0});
  attach_out_ = ctx.output<msg::Attachment>("attach", "where the device holds the virtual object, or that it lets go",
                                            Qos::reliable(4));
  arm_request_out_ = ctx.output<msg::ArmRequest>(
      "arm_request", "asks the arm to clear a fault that bad input caused, once the display's inputs are good again",
      Qos::reliable(8).one_writer());
  try {
    scene_ = haptics::load_scene(find_config_file(scene_path_));
  } catch (const std::exception& e) {
    ctx.reject("scene", e.what());
  }
}

void Supervisor::tick(Time now) {
  read_inputs(now.ns);
  if (mode_ != msg::MODE_FAULT) check_inputs(now.ns);
  switch (mode_) {
    case msg::MODE_IDLE:
      // An arm held by a fault (its stream lost while this display was away, say) starts only
      // through the fault's recovery: cleared on request, then idle -> surface as here.
      if (robot_ns_ >= 0 && robot_msg_.state() == msg::ARM_FAULT) {
        bad(std::string("the arm: ") + robot_msg_.reason().c_str(), now.ns);
        break;
      }
      hold_where_the_arm_stands(now.ns);
      // Every input there first (between processes they come one by one as DDS matches them),
      // and the arm following the hold.
      if (surface_.at_ns >= 0 && arm_follows(now.ns) && sent_ && wrench_ns_ >= 0 &&
          now.ns - wrench_ns_ <= wrench_timeout_ns_ && planner_ns_ >= 0 && near(surface_))
        enter(msg::MODE_SURFACE, now.ns, "");
      break;
    case msg::MODE_SURFACE:
      if (taking_over_)
        take_over(surface_, now.ns);
      else if (surface_.fresh)
        forward(surface_);
      watch_contact(now.ns);
      break;
    case msg::MODE_ADMITTANCE:
      if (taking_over_)
        take_over(admittance_, now.ns);
      else if (admittance_.fresh)
        forward(admittance_);
      watch_contact(now.ns);
      break;
    case msg::MODE_FAULT:
      hold_where_the_arm_stands(now.ns);
      recover(now.ns);
      break;
  }
  if (sent_ && !hold_unknown_) publish_setpoint(now.ns);
  if (now.ns - mode_sent_ns_ >= 100'000'000) publish_mode(now.ns);
}

// Idle or held: while the arm follows nothing, the hold is its measured pose, at rest; without a
// fresh measurement nothing is sent (a killed arm's last pose is no hold for its successor).
void Supervisor::hold_where_the_arm_stands(std::int64_t now_ns) {
  hold_unknown_ = false;
  if (arm_follows(now_ns)) return;  // (the last setpoint, which it follows)
  if (!have_device_ || now_ns - device_ns_ > wrench_timeout_ns_) {
    hold_unknown_ = true;
    return;
  }
  msgs::to_msg(device_, out_.pose());
  out_.twist() = geometry_msgs::Twist();
  out_.sensed_ns(0);
  sent_ = true;
}

// Forwards a source's setpoint; one that jumps too fast is a fault.
void Supervisor::forward(const Stream& s) {
  const double step = (msgs::to_eigen(s.sample.pose().position()) - msgs::to_eigen(out_.pose().position())).norm();
  const double dt = std::max(1e-3, seconds(elapsed_ns(s.sample.header().stamp_ns(), out_.header().stamp_ns())));
  if (sent_ && step > max_speed_ * dt + max_switch_step_)
    return bad("the " + std::string(mode_name(mode_)) + " setpoint jumped " + std::to_string(step * 1e3) + " mm",
               s.at_ns);
  out_.pose() = s.sample.pose();
  out_.twist() = s.sample.twist();
  out_.sensed_ns(s.sample.sensed_ns());
  sent_ = true;
}

// A new source takes over once it continues from the last setpoint.
void Supervisor::take_over(const Stream& s, std::int64_t now_ns) {
  if (s.fresh && s.at_ns >= switched_ns_ && near(s)) {
    taking_over_ = false;
    forward(s);
    return;
  }
  out_.twist() = geometry_msgs::Twist();  // hold meanwhile
  if (now_ns - switched_ns_ > switch_timeout_ns_)
    bad(std::string("the ") + mode_name(mode_) + " source did not continue from the last setpoint within " +
            std::to_string(seconds(switch_timeout_ns_)) + " s",
        now_ns);
}

void Supervisor::watch_contact(std::int64_t now_ns) {
  if (mode_ == msg::MODE_FAULT || !have_reading_ || !have_device_) return;
  // The user's force: the reading less the tool's weight, in the sensor's true orientation.
  const double force = haptics::user_load(reading_, device_, scene_.device, scene_.gravity).force.norm();
  const double hand_distance = now_ns - hand_ns_ <= 200'000'000 && hand_ns_ >= 0 ? plate_distance(hand_) : -1;
  switch (detector_.update(now_ns, force, hand_distance, mode_ == msg::MODE_ADMITTANCE, hand_sigma_)) {
    case ContactDetector::Event::kTouch:
      attach(now_ns);
      enter(msg::MODE_ADMITTANCE, now_ns, "touch: " + std::to_string(force) + " N");
      break;
    case ContactDetector::Event::kRelease:
      detach(now_ns);
      enter(msg::MODE_SURFACE, now_ns, "release");
      break;
    case ContactDetector::Event::kForeignForce:
      bad(std::to_string(force) + " N on the plate with the hand " + std::to_string(hand_distance) + " m (sigma " +
              std::to_string(hand_sigma_) + " m) away: something else touches the arm",
          now_ns);
      break;
    case ContactDetector::Event::kNone: break;
  }
}

double Supervisor::plate_distance(const Vec3& hand) const {
  const Vec3 local = device_.inverse() * hand;
  const Vec3 on_plate(std::clamp(local.x(), -scene_.device.plate_half.x(), scene_.device.plate_half.x()),
                      std::clamp(local.y(), -scene_.device.plate_half.y(), scene_.device.plate_half.y()), 0.0);
  return std::max(0.0, (local - on_plate).norm() - finger_radius_);
}

// The device holds the planner's feature where the arm is commanded to be.
void Supervisor::attach(std::int64_t now_ns) {
  std::string feature = planner_msg_.feature().c_str(), body = planner_msg_.body().c_str();
  if (body.empty() && scene_.device.body >= 0) body = scene_.models[static_cast<std::size_t>(scene_.device.body)].name;
  const auto obj = base_T_obj_.find(body);
  const Eigen::Isometry3d base_T_obj = obj != base_T_obj_.end() ? obj->second : initial_pose(body);
  fill_header(attach_msg_.header(), now_ns, attach_seq_++, "base");
  attach_msg_.attached(true);
  attach_msg_.body(body);
  attach_msg_.feature(feature);
  msgs::to_msg(base_T_obj.inverse() * msgs::to_isometry(out_.pose()), attach_msg_.obj_T_dev());
  attach_out_.write(attach_msg_);
  attached_ = true;
}

void Supervisor::detach(std::int64_t now_ns) {
  if (!attached_) return;
  fill_header(attach_msg_.header(), now_ns, attach_seq_++, "base");
  attach_msg_.attached(false);
  attach_out_.write(attach_msg_);
  attached_ = false;
}

Eigen::Isometry3d Supervisor::initial_pose(const std::string& body) const {
  const int i = scene_.body_index(body);
  return i >= 0 ? haptics::pose_of(scene_.initial[static_cast<std::size_t>(i)]) : Eigen::Isometry3d::Identity();
}

void Supervisor::enter(msg::DisplayModeKind mode, std::int64_t now_ns, const std::string& why) {
  if (mode != mode_) log(std::string(mode_name(mode_)) + " -> " + mode_name(mode) + (why.empty() ? "" : ": " + why));
  mode_ = mode;
  reason_ = why;
  report_health(mode == msg::MODE_FAULT ? Health::kHolding : Health::kOk, why);
  switched_ns_ = now_ns;
  taking_over_ = mode == msg::MODE_SURFACE || mode == msg::MODE_ADMITTANCE;  // (from the hold, at the start)
  detector_.reset();
  good_since_ns_ = -1;
  publish_mode(now_ns);
}

// Something is wrong: hold where the arm was sent, let go of the object, and say why.
void Supervisor::bad(const std::string& why, std::int64_t now_ns) {
  if (mode_ == msg::MODE_FAULT) return;
  out_.twist() = geometry_msgs::Twist();
  detach(now_ns);
  enter(msg::MODE_FAULT, now_ns, why);
}

void Supervisor::publish_setpoint(std::int64_t now_ns) {
  fill_header(out_.header(), now_ns, out_seq_++, "base");
  out_.child_frame_id("dev");
  const bool holding = mode_ == msg::MODE_FAULT || mode_ == msg::MODE_IDLE || taking_over_;
  out_.source(holding                         ? "supervisor/hold"
              : mode_ == msg::MODE_ADMITTANCE ? "supervisor/admittance"
                                              : "supervisor/surface");
  if (holding) out_.sensed_ns(0);  // a hold answers no sensor sample
  setpoint_out_.write(out_);
}

void Supervisor::publish_mode(std::int64_t now_ns) {
  fill_header(mode_msg_.header(), now_ns, mode_seq_++, "base");
  mode_msg_.mode(mode_);
  mode_msg_.reason(reason_.substr(0, 127));
  mode_out_.write(mode_msg_);
  mode_sent_ns_ = now_ns;
}

}  // namespace wysiwyf::display

WYSIWYF_COMPONENT(wysiwyf::display::Supervisor, "supervisor")
