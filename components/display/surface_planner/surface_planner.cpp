// surface_planner: the target, the plan and the path's progress (surface_planner.hpp says how).
#include "surface_planner.hpp"

#include <cmath>

namespace wysiwyf::display {

void SurfacePlanner::configure(Context& ctx) {
  ctx.summary("surface display: the plate to the feature the hand is about to touch, within ISO/TS 15066 SSM");
  scene_path_ = ctx.param<std::string>("scene", "scenes/cube_against_wall.yaml", "scene file with its features");
  urdf_ = ctx.param<std::string>("urdf", "robots/puma560.urdf", "robot description (as the arm's)");
  limits_.speed = ctx.param<double>("max_speed", 0.6, "m/s, the plate's top speed along its path", Range{0.01, 2});
  limits_.acceleration = ctx.param<double>("max_acceleration", 2.0, "m/s^2, along the path", Range{0.1, 20});
  limits_.angular_speed =
      ctx.param<double>("max_angular_speed", 3.0, "rad/s, the plate's top turning rate", Range{0.01, 10});
  limits_.angular_acceleration = ctx.param<double>("max_angular_acceleration", 12.0, "rad/s^2", Range{0.1, 100});
  inner_depth_ = ctx.param<double>(
      "inner_depth", 0.05, "m behind a face (inside the virtual object) the plate passes on its way", Range{0, 0.5});
  const double horizon = ctx.param<double>("prediction_horizon", 0.8, "s the hand's path is extrapolated", Range{0, 5});
  const double hysteresis = ctx.param<double>(
      "hysteresis", 0.03, "m another feature must be nearer the hand's path to take over", Range{0, 1});
  const double dwell = ctx.param<double>("switch_dwell", 0.1, "s it must stay nearer", Range{0, 5});
  const double penalty = ctx.param<double>(
      "unreachable_penalty", 0.05,
      "m a feature the arm cannot display counts farther from the hand's path (a tie goes to one it can)",
      Range{0, 10});
  chooser_ = std::make_unique<FeatureChooser>(horizon, hysteresis, dwell, penalty);
  accel_density_ = ctx.param<double>("hand_accel_density", 20.0, "the hand filter's white acceleration, (m/s^2)^2/Hz",
                                     Range{1e-3, 1e6});
  hand_timeout_ns_ = static_cast<std::int64_t>(
      ctx.param<double>("hand_timeout", 0.2, "s without a tracked hand before it counts as unknown", Range{0.001, 10}) *
      1e9);
  hand_max_lead_ns_ = static_cast<std::int64_t>(
      ctx.param<double>("hand_max_lead", 0.1,
                        "s a hand sample may be stamped ahead of this pipeline's clock (clocks of two machines)",
                        Range{0, 10}) *
      1e9);
  input_timeout_ns_ = static_cast<std::int64_t>(
      ctx.param<double>("input_timeout", 0.05, "s without joint states or device poses: a fault", Range{0.001, 10}) *
      1e9);
  finger_radius_ =
      ctx.param<double>("finger_radius", 0.01, "m, the fingertip's radius around the tracked point", Range{0, 0.1});
  // ISO/TS 15066 speed and separation monitoring, each constant with its source.
  ssm_.human_speed = ctx.param<double>(
      "human_speed", 1.6, "v_h, m/s: the hand's approach speed (ISO 13855 K = 1600 mm/s; ISO/TS 15066)", Range{0.1, 5});
  ssm_.reaction_time = ctx.param<double>(
      "reaction_time", 0.1,
      "T_r, s: from the hand moving to the arm reacting (tracking latency, planner period, the arm's tracking lag)",
      Range{0, 2});
  ssm_.braking_deceleration = ctx.param<double>(
      "braking_deceleration", 1.5,
      "a_s, m/s^2: the arm's assured deceleration along the plate's path (S_s = v^2/(2 a_s), T_s = v/a_s); the "
      "PUMA's joint acceleration limits hold it to about this",
      Range{0.1, 50});
  ssm_.intrusion = ctx.param<double>(
      "intrusion", 0.0, "C, m: reach past the tracked point (0: the fingertip itself is tracked)", Range{0, 1});
  ssm_.human_uncertainty = ctx.param<double>("human_uncertainty", 0.02, "Z_d, m: hand tracking error", Range{0, 1});
  ssm_.robot_uncertainty = ctx.param<double>(
      "robot_uncertainty", 0.01, "Z_r, m: the arm's position error (following error, calibration)", Range{0, 1});
  ssm_margin_ = ctx.param<double>("ssm_margin", 0.8,
                                  "share of the SSM-allowed approach speed the plan uses (the rest: the arm's "
                                  "tracking of it lags and overshoots)",
                                  Range{0.1, 1});
  speed_without_hand_ = ctx.param<double>(
      "speed_without_hand", 0.25, "m/s at most while no hand is tracked (ISO 10218-1's reduced speed)", Range{0, 2});
  in_place_ =
      ctx.param<double>("in_place_tolerance", 0.001, "m: the plate this near its target is in place", Range{1e-5, 0.1});
  still_speed_ = ctx.param<double>("still_speed", 0.002, "m/s: the plate slower than this is still", Range{1e-5, 1});

  hand_in_ = ctx.input<msg::HandPosition>("hand", "the tracked fingertip (base frame)", Qos::sensor(8));
  objects_in_ = ctx.input<msg::ObjectState>("objects", "the virtual objects (admittance_sim)", Qos::reliable(64));
  joints_in_ = ctx.input<msg::JointState>("joint_state", "the arm's measured joints", Qos::sensor(4));
  device_in_ = ctx.input<msg::PoseStamped>("device_pose", "the plate's measured pose base_T_dev", Qos::sensor(4));
  mode_in_ = ctx.input<msg::DisplayMode>("mode", "the display's mode (the supervisor)", Qos::reliable(8));
  commanded_in_ =
      ctx.input<msg::CartesianSetpoint>("commanded", "what the arm is commanded (robot/setpoint)", Qos::reliable(32));
  setpoint_out_ = ctx.output<msg::CartesianSetpoint>("setpoint", "base_T_dev for surface mode (source surface)");
  status_out_ =
      ctx.output<msg::PlannerStatus>("status", "target feature, state, ETA, hand ETA, reason", Qos::reliable(8));
  dt_ = ctx.period_ns() > 0 ? seconds(ctx.period_ns()) : 1e-3;
  try {
    scene_ = haptics::load_scene(find_config_file(scene_path_));
    if (scene_.features.empty())
      ctx.reject("scene", "'" + scene_path_ + "' declares no features: for the plate to display");
  } catch (const std::exception& e) {
    ctx.reject("scene", e.what());
  }
  try {
    model_ = robot::load_display_arm(find_config_file(urdf_), "dev");
    q_ = robot::JointVector::Zero(model_->dof());
    clearance_ = std::make_unique<robot::ArmClearance>(*model_);
    monitor_ = std::make_unique<SeparationMonitor>(*model_, *clearance_, ssm_, finger_radius_, speed_without_hand_);
  } catch (const std::exception& e) {
    ctx.reject("urdf", e.what());
  }
}

void SurfacePlanner::activate() {
  hand_ = HandFilter(accel_density_);
  for (const auto& initial : scene_.initial) base_T_obj_.push_back(haptics::pose_of(initial));
}

void SurfacePlanner::tick(Time now) {
  read_inputs(now.ns);
  status_.state(msg::PLAN_IDLE);
  status_.reason("");
  if (!have_joints_ || !have_device_) {
    publish_status(now.ns);
    return;  // nothing to plan from yet
  }
  if (now.ns - joints_ns_ > input_timeout_ns_ || now.ns - device_ns_ > input_timeout_ns_) {
    fault(now.ns, "no joint state or device pose for " +
                      std::to_string(seconds(now.ns - std::min(joints_ns_, device_ns_))) + " s");
    return;
  }
  if (!have_cmd_) cmd_ = device_, have_cmd_ = true;  // start where the plate is
  if (mode_ != msg::MODE_SURFACE) {
    // Follow what the arm is commanded, so surface mode starts from there.
    if (have_commanded_) cmd_ = commanded_;
    path_.clear();
    kappa_ = 0;
    replan_ = false;
    chooser_->reset();
    target_feature_ = nullptr;
    was_in_place_ = false;
    status_.reason("not in surface mode");
    sensed_ns_ = 0;
    publish(now.ns, Vec3::Zero(), Vec3::Zero());
    publish_status(now.ns);
    return;
  }
  const bool hand_known = hand_.valid() && elapsed_ns(now.ns, hand_.stamp_ns()) <= hand_timeout_ns_;
  const Vec3 hand = hand_known ? hand_.position(now.ns) : Vec3::Zero();
  sensed_ns_ = hand_known ? hand_.stamp_ns() : 0;  // the hand sample this tick's setpoint answers
  if (hand_known) choose_target(hand, now.ns);
  // The path's clock runs at kappa: 1 at full speed, lower where speed and separation monitoring
  // says so; it may fall only as fast as the arm brakes, and rises over rise_time.
  if (replan_ && !moving()) {
    replan_ = false;
    if (target_feature_) plan(*target_feature_, planned_obj_);
  }
  const double ssm = !hand_known    ? monitor_->kappa_without_hand(path_)
                     : path_.done() ? (monitor_->measure(q_, hand), 1.0)
                                    : monitor_->kappa(path_, q_, hand);
  const double target = replan_ ? 0.0 : std::min(1.0, ssm_margin_ * ssm);
  kappa_ = target < kappa_ ? std::max(target, monitor_->braking_kappa(path_, kappa_, dt_))
                           : std::min(target, kappa_ + dt_ / 0.2);
  if (!path_.done()) {
    path_.advance(dt_, kappa_);
    cmd_ = path_.pose();
    // The last half millimetre of a minimum-jerk segment creeps: take it (well within Z_r).
    if ((path_.goal().translation() - cmd_.translation()).norm() < 0.5 * in_place_ &&
        Eigen::Quaterniond(path_.goal().linear()).angularDistance(Eigen::Quaterniond(cmd_.linear())) < 0.002) {
      cmd_ = path_.goal();
      path_.clear();
    }
  }
  report(now.ns, hand_known, hand, ssm);
  publish(now.ns, path_.velocity() * kappa_, path_.angular_velocity() * kappa_);
}

// The feature the hand goes for; a new one (or its object moved) gets a new path.
void SurfacePlanner::choose_target(const Vec3& hand, std::int64_t now_ns) {
  // The features found out of reach, while their objects have not moved since.
  unreachable_set_.clear();
  for (const auto& [feature, where] : unreachable_at_)
    if ((base_T_obj_[static_cast<std::size_t>(feature->body)].translation() - where).norm() <= 0.002)
      unreachable_set_.insert(feature);
  const haptics::DisplayFeature* f =
      chooser_->choose(scene_, base_T_obj_, hand, hand_.significant_velocity(), now_ns, &unreachable_set_);
  if (!f) return;
  const Eigen::Isometry3d& base_T_obj = base_T_obj_[static_cast<std::size_t>(f->body)];
  const bool moved = target_feature_ == f && (base_T_obj.translation() - planned_obj_.translation()).norm() > 0.002;
  if (f == target_feature_ && !moved) return;
  target_feature_ = f;
  planned_obj_ = base_T_obj;
  // A new path starts at rest: while the plate moves, brake first (a setpoint stopping dead
  // would leave the lagging arm to overshoot it), then plan from where it stopped.
  if (moving()) {
    replan_ = true;
    return;
  }
  plan(*f, base_T_obj);
}

// A path from the commanded pose to a plate pose displaying `f`, through the object's inside.
void SurfacePlanner::plan(const haptics::DisplayFeature& f, const Eigen::Isometry3d& base_T_obj) {
  unreachable_.clear();
  const Vec3 out_of_target = base_T_obj.linear() * f.normal;
  std::vector<Vec3> via;
  // Leaving a face of this object: back into it first.
  const Vec3 z_now = cmd_.linear().col(2);
  const Eigen::Isometry3d obj_T_cmd = base_T_obj.inverse() * cmd_;
  const Vec3 half = scene_.models[static_cast<std::size_t>(f.body)].half_extents;
  const bool on_object = (obj_T_cmd.translation().cwiseAbs() - half).maxCoeff() < 0.02;
  for (const Eigen::Isometry3d& target : plate_poses(f, base_T_obj, cmd_)) {
    via.clear();
    // Near it already (the same face, a little off): straight there; else back into the object
    // and out through the target face.
    const bool near = (target.translation() - cmd_.translation()).norm() <= 0.005 &&
                      Eigen::Quaterniond(target.linear()).angularDistance(Eigen::Quaterniond(cmd_.linear())) <= 0.05;
    if (!near) {
      if (on_object) via.push_back(cmd_.translation() - z_now * inner_depth_);  // back into the object
      via.push_back(target.translation() - out_of_target * inner_depth_);       // out through the target face
    }
    PlatePath path(limits_);
    path.plan(cmd_, via, target);
    robot::JointVector q_end;
    const std::string why = path_reachable(*model_, path, q_, q_end);
    if (why.empty()) {
      path_ = path;
      target_ = target;
      unreachable_at_.erase(&f);
      return;
    }
    unreachable_ = why;
  }
  path_.clear();  // stay where it is
  target_ = cmd_;
  unreachable_at_[&f] = base_T_obj.translation();
  warn_once("unreachable " + f.name, "'" + f.name + "' is out of the arm's reach: " + unreachable_);
}

}  // namespace wysiwyf::display

WYSIWYF_COMPONENT(wysiwyf::display::SurfacePlanner, "surface_planner")
