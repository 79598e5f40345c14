// admittance_sim: the admittance display mode (paper sections 2.3 and 4). Every tick it takes
// the force the user applies (the wrist F/T sensor), moves the virtual object by rigid-body
// dynamics with non-penetration constraints (Baraff's contact LCP on SUNDIALS) and sends
// the object's motion to the robot as the device setpoint: base_T_dev = base_T_obj * obj_T_dev
// (the virtual environment frame is the robot base, eq. 6).
//
// Where the device is attached: the scene file's device (body and face) from the start, or, with
// attached_at_start false, only once an `attach` message says so (the supervisor, entering
// admittance display mode, attaches the device to the feature the surface planner chose, at the
// pose where the device is, so the first setpoint is the last one the arm had). Detached, the
// user's wrench does not act on the object and no setpoint is published.
//
// The setpoint is the held object's motion averaged over a short window centred on now, the
// future half from a look-ahead world (setpoint_preview.hpp): the arm brakes ahead of an impact
// and arrives with the object instead of running past it. It is led by the arm's give under the
// user's push (arm_yield.hpp), learned from the plate's measured pose.
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

#include "arm_yield.hpp"
#include "setpoint_preview.hpp"
#include "scene/scene.hpp"
#include "rigid_body/world.hpp"
#include "scene/tool_load.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::haptics {

class AdmittanceSim final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("admittance display: rigid bodies with contact LCP on SUNDIALS, driven by the user's wrench");
    scene_path_ =
        ctx.param<std::string>("scene", "scenes/cube_on_table.yaml",
                               "scene file; relative paths are looked up in the working directory, then config/");
    max_force_ = ctx.param<double>("max_user_force", 200.0, "user forces above this are clipped (N)", Range{1, 2000});
    rtol_ = ctx.param<double>(
        "rtol", kHapticRtol,
        "the integrator's relative tolerance (absolute: 1e-2 of it); 1e-7 keeps a pushed cube within 5 um "
        "of its exact motion over 10 s",
        Range{1e-14, 1e-3});
    const auto integrator = ctx.param<std::string>(
        "integrator", "runge_kutta",
        "runge_kutta (ARKODE's explicit 3(2): a box under a held push in one step) or adams (CVODE, orders up to "
        "12: long smooth free flight at tight tolerances)");
    if (integrator == "adams")
      integrator_ = Integrator::kAdams;
    else if (integrator != "runge_kutta")
      ctx.reject("integrator", "'" + integrator + "' is neither runge_kutta nor adams");
    preview_window_ = ctx.param<double>(
        "preview_window", 0.03,
        "s, the window the setpoint averages the object's motion over, centred on now (the future half looked "
        "ahead): the arm brakes ahead of impacts; 0 sends the object's motion as it is",
        Range{0, 0.2});
    yield_rate_ = ctx.param<double>(
        "yield_rate", 5.0,
        "1/s, how fast the arm's compliance under the user's push is learned from device_pose (0: not learned, the "
        "setpoint not led)",
        Range{0, 1000});
    max_compliance_ =
        ctx.param<double>("max_compliance", 1e-3, "m/N, the most the learned compliance may be", Range{0, 0.01});
    attached_ = ctx.param<bool>("attached_at_start", true,
                                "the scene's device attachment holds from the start (false: wait for `attach`)");
    attach_in_ =
        ctx.input<msg::Attachment>("attach",
                                   "where the device holds the object, or that it lets go (optional: without it the "
                                   "scene's attachment holds as attached_at_start says)",
                                   Qos::reliable(4).optional_input());
    wrench_ = ctx.input<msg::WrenchStamped>("wrench", "the wrist F/T sensor: user push plus tool weight, sensor frame",
                                            Qos::sensor(8));
    device_pose_ =
        ctx.input<msg::PoseStamped>("device_pose",
                                    "measured base_T_dev (optional): where the sensor really is, for removing the "
                                    "tool's weight; without it, where the object says the device should be",
                                    Qos::sensor(4).optional_input());
    setpoint_ =
        ctx.output<msg::CartesianSetpoint>("setpoint", "base_T_dev and its twist for the robot (source admittance)");
    objects_ =
        ctx.output<msg::ObjectState>("objects", "pose, twist and contacts of every dynamic body", Qos::reliable(16));
    dt_ = ctx.period_ns() > 0 ? static_cast<double>(ctx.period_ns()) * 1e-9 : 1e-3;
    try {
      scene_ = load_scene(find_config_file(scene_path_));  // reported with the scene file's line before anything starts
    } catch (const std::exception& e) {
      return ctx.reject("scene", e.what());
    }
    if (scene_.device.body < 0) ctx.reject("scene", "'" + scene_path_ + "' has no device: attachment");
    body_ = scene_.device.body;
    obj_T_dev_ = scene_.device.obj_T_dev;
  }

  void activate() override {
    WorldParams p;
    p.gravity = scene_.gravity;
    p.rtol = rtol_;
    p.atol = rtol_ * 1e-2;
    p.integrator = integrator_;
    world_ = std::make_unique<World>(scene_.models, scene_.initial, p);
    const auto half = static_cast<std::size_t>(std::lround(0.5 * preview_window_ / dt_));
    preview_ = std::make_unique<SetpointPreview>(half, dt_);
    ahead_ = half > 0 ? std::make_unique<World>(scene_.models, scene_.initial, p) : nullptr;
    preview_->restart(pose_of(*world_, body_) * obj_T_dev_);
    yield_ = std::make_unique<ArmYield>(yield_rate_, max_compliance_, kMinYieldForce);
    contact_names_.clear();
    for (const BodyModel& m : scene_.models) contact_names_.emplace_back(m.name);
  }

  void tick(Time now) override {
    while (attach_in_.take(attach_msg_)) take_attachment();
    // STEP 1: the user's wrench, held until the next sample.
    while (take_checked(wrench_, sample_)) {  // (a corrupt sample is ignored: never moved on)
      have_reading_ = true;
      sensed_ns_ = sample_.header().stamp_ns();
      reading_.force = msgs::to_eigen(sample_.wrench().force());
      reading_.torque = msgs::to_eigen(sample_.wrench().torque());
      if (reading_.force.norm() > max_force_) reading_.force *= max_force_ / reading_.force.norm();
    }
    while (take_checked(device_pose_, device_msg_)) {
      const Eigen::Isometry3d T = msgs::to_isometry(device_msg_.pose());
      const std::int64_t stamp = device_msg_.header().stamp_ns();
      if (attached_ && have_device_pose_ && stamp > device_stamp_)
        yield_->measured(stamp, T.translation(), user_force_, static_cast<double>(stamp - device_stamp_) * 1e-9);
      measured_base_T_dev_ = T, have_device_pose_ = true, device_stamp_ = stamp;
    }
    const int body = body_;
    const Eigen::Isometry3d base_T_obj = pose_of(*world_, body);
    // The sensor is where the robot holds it; if the robot lags or holds, that is not where the
    // object says, and the tool's weight must be removed in the sensor's true orientation.
    const Eigen::Isometry3d base_T_dev = have_device_pose_ ? measured_base_T_dev_ : base_T_obj * obj_T_dev_;
    const Eigen::Isometry3d base_T_sensor = base_T_dev * scene_.device.dev_T_sensor;
    // Until the sensor has said anything, nobody pushes (a zero reading would be minus the tool's
    // weight); detached, the user's hand is on the plate, not on the object.
    const BodyWrench user = have_reading_ && attached_
                                ? user_wrench_on_body(reading_, base_T_sensor, world_->state(body).x,
                                                      scene_.device.tool_mass, scene_.device.tool_com, scene_.gravity)
                                : BodyWrench{};
    world_->set_external_wrench(body, user.force, user.torque);
    user_force_ = user.force;
    // STEP 2-6.
    const StepReport report = world_->step(dt_);
    if (report.integration_failures > 0)
      log("the step could not be integrated; the objects hold: " + world_->last_failure());
    if (report.lcp_failures > 0)
      log("contact LCP found no solution in this step (" + std::to_string(report.lcp_failures) + " time(s))");
    // STEP 7: the motion command.
    publish(now);
  }

 private:
  // An attach or detach from the supervisor; a wrong one is refused and changes nothing.
  void take_attachment() {
    if (!attach_msg_.attached()) {
      if (attached_) log("detached from " + world_->model(body_).name);
      attached_ = false;
      return;
    }
    const int body = scene_.body_index(attach_msg_.body().c_str());
    if (body < 0 || !scene_.models[body].dynamic)
      return reject(attach_in_,
                    "body '" + std::string(attach_msg_.body().c_str()) + "' is not a dynamic body of the scene");
    if (const std::string why = problem(attach_msg_); !why.empty()) return reject(attach_in_, why);
    body_ = body;
    obj_T_dev_ = msgs::to_isometry(attach_msg_.obj_T_dev());
    attached_ = true;
    preview_->restart(pose_of(*world_, body_) * obj_T_dev_);
    smooth_ = false;
    yield_->restart();
    log("attached to " + scene_.models[body].name + " (" + attach_msg_.feature().c_str() + ")");
  }

  static Eigen::Isometry3d pose_of(const World& world, int body) { return haptics::pose_of(world.state(body)); }

  // The held device pose over the next half window. Where the held body may hit something within
  // it (a gap of it watched, or faster than the margin in the window), from the world as it is
  // now with the user's wrench held, in a second world (a step that cannot be integrated holds
  // the bodies where they were); elsewhere its motion is smooth over milliseconds and is
  // extrapolated at its current velocity and acceleration, for a tenth of the cost.
  void look_ahead() {
    std::vector<Eigen::Isometry3d>& future = preview_->future();
    const auto k = world_->kinematics(body_);
    const Eigen::Isometry3d base_T_obj = pose_of(*world_, body_);
    // (the acceleration of the last tick, where that was smooth too: not across an impact)
    const Eigen::Vector3d accel = smooth_ ? Eigen::Vector3d((k.v - last_v_) / dt_) : Eigen::Vector3d::Zero();
    last_v_ = k.v;
    const double horizon = dt_ * static_cast<double>(future.size());
    smooth_ = !(world_->watching(body_) || k.v.norm() * horizon > 0.5 * world_->margin());
    if (!smooth_) {
      // Steps of kLookAheadStride ticks (the integrator finds an impact inside one to the same
      // tolerance), the ticks between them interpolated.
      ahead_->copy_state_from(*world_);
      Eigen::Isometry3d before = pose_of(*world_, body_) * obj_T_dev_;
      for (std::size_t done = 0; done < future.size();) {
        const std::size_t n = std::min(kLookAheadStride, future.size() - done);
        ahead_->step(dt_ * static_cast<double>(n));
        const Eigen::Isometry3d after = pose_of(*ahead_, body_) * obj_T_dev_;
        const Eigen::Quaterniond q0(before.linear()), q1(after.linear());
        for (std::size_t i = 1; i <= n; ++i) {
          const double f = static_cast<double>(i) / static_cast<double>(n);
          Eigen::Isometry3d& pose = future[done + i - 1];
          pose.linear() = q0.slerp(f, q1).toRotationMatrix();
          pose.translation() = (1 - f) * before.translation() + f * after.translation();
        }
        before = after;
        done += n;
      }
      return;
    }
    for (std::size_t i = 0; i < future.size(); ++i) {
      const double tau = dt_ * static_cast<double>(i + 1);
      Eigen::Isometry3d T = base_T_obj;
      T.translation() += k.v * tau + 0.5 * tau * tau * accel;
      const Eigen::Vector3d turn = k.omega * tau;
      if (turn.norm() > 0) T.linear() = Eigen::AngleAxisd(turn.norm(), turn.normalized()) * T.linear();
      future[i] = T * obj_T_dev_;
    }
  }

  void publish(Time now) {
    if (attached_) {
      const auto k = world_->kinematics(body_);
      const Eigen::Isometry3d base_T_dev = pose_of(*world_, body_) * obj_T_dev_;
      fill_header(setpoint_msg_.header(), now.ns, seq_, "base");
      setpoint_msg_.child_frame_id("dev");
      yield_->object_at(now.ns, base_T_dev.translation());
      PreviewedSetpoint sp;
      if (ahead_) {
        preview_->record(base_T_dev);
        look_ahead();
        sp = preview_->setpoint();
      } else {
        sp.pose = base_T_dev;
        sp.linear = k.point_velocity(base_T_dev.translation(), world_->state(body_).x);
        sp.angular = k.omega;
      }
      sp.pose.translation() += yield_->lead(user_force_);
      msgs::to_msg(sp.pose, setpoint_msg_.pose());
      msgs::to_msg(sp.linear, sp.angular, setpoint_msg_.twist());
      setpoint_msg_.source("admittance");
      setpoint_msg_.sensed_ns(sensed_ns_);
      setpoint_.write(setpoint_msg_);
    }

    const std::vector<ActiveContact>& resting = world_->resting_contacts();
    sort_contacts_by_body(resting);
    for (int i = 0; i < world_->body_count(); ++i) {
      if (!world_->model(i).dynamic) continue;
      const auto ki = world_->kinematics(i);
      fill_header(object_msg_.header(), now.ns, seq_, "v_env");
      object_msg_.child_frame_id(world_->model(i).name);
      msgs::to_msg(pose_of(*world_, i), object_msg_.pose());
      msgs::to_msg(ki.v, ki.omega, object_msg_.twist());
      // (the last message's contacts are written over: no message built and copied per contact)
      std::vector<msg::Contact>& out = object_msg_.contacts();
      const std::vector<std::size_t>& mine = contacts_of_[static_cast<std::size_t>(i)];
      out.resize(mine.size());
      for (std::size_t k = 0; k < mine.size(); ++k) {
        const ActiveContact& c = resting[mine[k]];
        msg::Contact& m = out[k];
        msgs::to_msg(c.point.p, m.position());
        msgs::to_msg(c.feature.a == i ? c.point.n : Vec3(-c.point.n), m.normal());  // (n: out of b, into a)
        m.gap(c.point.gap);
        m.force(c.force);
        m.kind(msg::CONTACT_RESTING);
        m.other(contact_names_[static_cast<std::size_t>(c.feature.a == i ? c.feature.b : c.feature.a)]);
      }
      objects_.write(object_msg_);
    }
    ++seq_;
  }

  // Each dynamic body's resting contacts (the first kContactsPerObject, in the world's order), in
  // one pass over them, not one pass for each body.
  void sort_contacts_by_body(const std::vector<ActiveContact>& resting) {
    contacts_of_.resize(static_cast<std::size_t>(world_->body_count()));
    for (std::vector<std::size_t>& list : contacts_of_) list.clear();
    for (std::size_t c = 0; c < resting.size(); ++c)
      for (const int i : {resting[c].feature.a, resting[c].feature.b}) {
        std::vector<std::size_t>& list = contacts_of_[static_cast<std::size_t>(i)];
        if (world_->model(i).dynamic && list.size() < kContactsPerObject) list.push_back(c);
      }
  }

  static constexpr std::size_t kContactsPerObject = 32;  // (ObjectState's contacts: a bounded message)
  std::string scene_path_;
  double max_force_ = 200, rtol_ = kHapticRtol, dt_ = 1e-3;
  Integrator integrator_ = Integrator::kRungeKutta;
  Scene scene_;
  bool attached_ = true;
  int body_ = -1;                                                // the body the device holds
  Eigen::Isometry3d obj_T_dev_ = Eigen::Isometry3d::Identity();  // where on it
  msg::Attachment attach_msg_;
  Input<msg::Attachment> attach_in_;
  std::unique_ptr<World> world_;
  double preview_window_ = 0.02;
  std::unique_ptr<SetpointPreview> preview_;
  std::unique_ptr<World> ahead_;                      // the look-ahead (none without a preview window)
  Eigen::Vector3d last_v_ = Eigen::Vector3d::Zero();  // the held body's velocity a tick ago
  static constexpr std::size_t kLookAheadStride = 4;  // ticks per step of the look-ahead world
  static constexpr double kMinYieldForce = 1.0;       // N: weaker pushes teach nothing of the arm's give
  double yield_rate_ = 5, max_compliance_ = 1e-3;
  std::unique_ptr<ArmYield> yield_;
  Vec3 user_force_ = Vec3::Zero();  // the user's force on the held body, the last tick's (base frame)
  std::int64_t device_stamp_ = 0;   // of the last measured device pose
  bool smooth_ = false;             // the last tick's motion was extrapolated (no impact could come)
  SensorReading reading_;
  bool have_device_pose_ = false;
  Eigen::Isometry3d measured_base_T_dev_ = Eigen::Isometry3d::Identity();
  msg::PoseStamped device_msg_;
  Input<msg::PoseStamped> device_pose_;
  bool have_reading_ = false;
  std::int64_t sensed_ns_ = 0;  // the stamp of the wrench sample the motion answers
  std::uint64_t seq_ = 0;
  msg::WrenchStamped sample_;
  msg::CartesianSetpoint setpoint_msg_;
  msg::ObjectState object_msg_;
  std::vector<std::vector<std::size_t>> contacts_of_;  // publish's: each body's resting contacts
  // The bodies' names as a Contact's `other` holds them (a bounded string), converted once rather
  // than at every contact of every tick
  std::vector<std::decay_t<decltype(std::declval<msg::Contact&>().other())>> contact_names_;
  Input<msg::WrenchStamped> wrench_;
  Output<msg::CartesianSetpoint> setpoint_;
  Output<msg::ObjectState> objects_;
};

}  // namespace wysiwyf::haptics

WYSIWYF_COMPONENT(wysiwyf::haptics::AdmittanceSim, "admittance_sim")
