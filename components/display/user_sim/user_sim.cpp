// user_sim: a scripted user, in terms of the virtual scene (what a person sees), not of the robot:
// reach for a named feature, touch it, push with a force, drag, release, withdraw, reach another.
// It drives the fingertip that arm_sim simulates (hand_target: arm_sim's impedance pulls the
// finger there, and the plate's contact stops it), so a push is a target behind the surface by
// force / hand_stiffness. It does not know where the robot is: if the plate is not on the virtual
// surface when the finger gets there, the finger passes through it. What happened is published
// as UserEvents: a reach, and then a TOUCH (the finger met the plate on the virtual surface) or a
// MISS (it passed through, or was stopped short of it), pushes, releases, withdrawals.
#include <cmath>
#include <map>
#include <memory>

#include "reach_path.hpp"
#include "scene/scene.hpp"
#include "user_script.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::display {

namespace {

using Vec3 = Eigen::Vector3d;

// Minimum jerk from 0 to 1 over tau in [0, 1] (Flash & Hogan 1985): how people move a hand.
double min_jerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
}

// The hand pointing along `direction` (its x, the finger), the back of the hand up (its z as near
// base +z as the finger allows; toward base +x when the finger points straight up or down).
Eigen::Quaterniond pointing(const Vec3& direction) {
  const Vec3 x = direction.normalized();
  const Vec3 up = std::abs(x.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX();
  const Vec3 z = (up - up.dot(x) * x).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x, R.col(1) = z.cross(x), R.col(2) = z;
  return Eigen::Quaterniond(R);
}

}  // namespace

class UserSim final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("scripted user in terms of the virtual scene: reach, touch, push, drag, release, withdraw");
    scene_path_ = ctx.param<std::string>("scene", "scenes/cube_against_wall.yaml", "scene file with its features");
    const auto script = ctx.param<std::vector<std::string>>(
        "script", {"reach cube +x knob", "push 3 1.0", "release 0.3", "withdraw 0.15 0.6"},
        "the user's actions, one a line: reach FEATURE [at U V] [speed V], push F T, drag DX DY DZ T, release T, "
        "withdraw D T, move X Y Z T, wait T");
    const auto start = ctx.param<std::array<double, 3>>(
        "start", {1.1, 0.0, 0.2}, "where the fingertip is at the start, base frame, m (arm_sim's hand_park)");
    hand_k_ =
        ctx.param<double>("hand_stiffness", 500.0, "N/m: arm_sim's impedance from target to fingertip", Range{1, 1e5});
    finger_radius_ = ctx.param<double>("finger_radius", 0.01, "m: arm_sim's fingertip radius", Range{0.001, 0.1});
    press_ = ctx.param<double>(
        "touch_press", 0.003,
        "a reach aims this far behind the surface (a touch of press x stiffness newtons: 1.5 N, below the "
        "supervisor's 2 N contact threshold), m",
        Range{0.001, 0.05});
    miss_depth_ = ctx.param<double>("miss_depth", 0.0015,
                                    "the finger this far past the virtual surface: the plate was not there (a miss), m",
                                    Range{0.0005, 0.05});
    if (miss_depth_ >= press_)
      ctx.reject("miss_depth", "must be less than touch_press (" + std::to_string(press_) +
                                   " m): a finger that meets no plate stops at touch_press behind the surface");
    stop_when_done_ = ctx.param<bool>("stop_when_done", false, "end the run when the script is done");
    objects_in_ =
        ctx.input<msg::ObjectState>("objects",
                                    "optional: where the virtual objects are (admittance_sim); without it, where "
                                    "the scene puts them",
                                    Qos::reliable(64).optional_input());
    hand_in_ = ctx.input<msg::PoseStamped>("hand_pose", "where the fingertip really is (arm_sim)", Qos::sensor(4));
    target_out_ = ctx.output<msg::PoseStamped>(
        "hand_target", "where the user moves the fingertip, base frame; the hand's orientation: x along the finger");
    events_out_ =
        ctx.output<msg::UserEvent>("events", "reach, touch or miss, push, release, withdraw, done", Qos::reliable(32));
    target_ = Vec3(start[0], start[1], start[2]);
    try {
      scene_ = haptics::load_scene(find_config_file(scene_path_));
    } catch (const std::exception& e) {
      return ctx.reject("scene", e.what());
    }
    try {
      actions_ = parse_user_script(script, scene_);
    } catch (const std::invalid_argument& e) {
      ctx.reject("script", e.what());
    }
  }

  void activate() override {
    for (const auto& initial : scene_.initial) base_T_obj_.push_back(haptics::pose_of(initial));
  }

  void tick(Time now) override {
    while (take_checked(objects_in_, object_msg_)) {
      const int body = scene_.body_index(object_msg_.child_frame_id().c_str());
      if (body < 0) continue;  // another scene's body: not one the user sees
      base_T_obj_[static_cast<std::size_t>(body)] = msgs::to_isometry(object_msg_.pose());
    }
    while (hand_in_.take(hand_msg_)) {
      const Vec3 p = msgs::to_eigen(hand_msg_.pose().position());
      if (p.allFinite())
        finger_ = p, have_finger_ = true;
      else
        reject(hand_in_, "a non-finite position");
    }
    step(now.ns);
    judge_touch(now.ns);
    fill_header(target_msg_.header(), now.ns, seq_++, "base");
    target_msg_.child_frame_id("hand");
    msgs::to_msg(target_, hand_q_, target_msg_.pose());
    target_out_.write(target_msg_);
  }

  void deactivate() override {
    log("script " + std::string(index_ >= actions_.size() ? "done" : "not done") + ": " + std::to_string(contact_) +
        " reach(es), " + std::to_string(hits_) + " hit(s), " + std::to_string(misses_) + " miss(es)");
  }

 private:
  // Where the current contact's surface point is now (it moves with its body), and its normal.
  Vec3 surface_point() const { return body_pose() * (touch_obj_ + offset_obj_); }
  Vec3 surface_normal() const { return body_pose().linear() * normal_obj_; }
  const Eigen::Isometry3d& body_pose() const { return base_T_obj_[static_cast<std::size_t>(body_)]; }
  // The fingertip's centre target for a force f on the surface (0: just touching).
  Vec3 pressing(double force) const { return surface_point() + surface_normal() * (finger_radius_ - force / hand_k_); }

  // Runs the current action at now_ns; moves on when it is over.
  void step(std::int64_t now_ns) {
    if (index_ >= actions_.size()) {
      if (!done_) {
        done_ = true;
        event(msg::USER_DONE, now_ns);
        if (stop_when_done_) request_stop("the user's script is done");
      }
      return;
    }
    const UserAction& a = actions_[index_];
    if (!begun_) {
      action_start_ns_ = now_ns;
      action_from_ = target_;
      begin(a, now_ns);
      begun_ = true;
    }
    const double t = static_cast<double>(now_ns - action_start_ns_) * 1e-9;
    const double tau = duration_ > 0 ? t / duration_ : 1.0;
    const double s = min_jerk(tau);
    switch (a.kind) {
      case UserAction::Kind::kReach:
        target_ = reach_.at(s, pressing(hand_k_ * press_), surface_normal());
        hand_q_ = q_from_.slerp(s, pointing(-surface_normal()));  // the finger turns toward the face
        break;
      case UserAction::Kind::kPush: {
        const double ramp = std::min(0.3, duration_ / 3);
        force_ = force_from_ + min_jerk(t / ramp) * (a.force - force_from_);
        target_ = pressing(force_);
        break;
      }
      case UserAction::Kind::kDrag: {
        const Vec3 along = a.vector - surface_normal() * surface_normal().dot(a.vector);  // in the surface's plane
        offset_obj_ = offset_from_ + body_pose().linear().transpose() * (s * along);
        target_ = pressing(force_);
        break;
      }
      case UserAction::Kind::kRelease:
        force_ = force_from_ * (1 - s);
        target_ = pressing(force_);
        break;
      case UserAction::Kind::kWithdraw: target_ = action_from_ + s * a.distance * surface_normal(); break;
      case UserAction::Kind::kMove: target_ = action_from_ + s * (a.vector - action_from_); break;
      case UserAction::Kind::kWait: break;
    }
    // A reach is over when the finger has met the surface or missed it (a person feels which
    // before doing anything else); until then the finger keeps pressing toward it.
    if (tau >= 1.0 && !(a.kind == UserAction::Kind::kReach && !judged_)) {
      ++index_;
      begun_ = false;
    }
  }

  void begin(const UserAction& a, std::int64_t now_ns) {
    duration_ = a.duration;
    force_from_ = force_;
    offset_from_ = offset_obj_;
    switch (a.kind) {
      case UserAction::Kind::kReach: {
        const haptics::DisplayFeature& f = *a.feature;
        feature_ = &f;
        body_ = f.body;
        touch_obj_ = f.touch + a.u * f.touch_u + a.v * f.touch_v;
        normal_obj_ = f.normal;
        offset_obj_ = offset_from_ = Vec3::Zero();
        force_ = force_from_ = 0;
        q_from_ = hand_q_;
        // Around the object, not through it: clear of it by the finger and a centimetre.
        reach_ = reach_around(action_from_, pressing(hand_k_ * press_), surface_normal(), body_pose(),
                              scene_.models[static_cast<std::size_t>(body_)].half_extents, finger_radius_ + 0.01);
        // Minimum jerk peaks at 1.875 times the mean speed.
        duration_ = std::max(0.2, 1.875 * reach_.length(pressing(hand_k_ * press_), surface_normal()) / a.speed);
        ++contact_;
        arrived_ns_ = -1;
        judged_ = false;
        reach_end_ns_ = now_ns + static_cast<std::int64_t>(duration_ * 1e9);
        event(msg::USER_REACH, now_ns);
        break;
      }
      case UserAction::Kind::kPush: event(msg::USER_PUSH, now_ns, a.force); break;
      case UserAction::Kind::kRelease: event(msg::USER_RELEASE, now_ns); break;
      case UserAction::Kind::kWithdraw: event(msg::USER_WITHDRAW, now_ns); break;
      default: break;
    }
  }

  // Hit or miss of the current reach, from where the finger really is against the virtual object:
  // a hit when it has rested on the touched face for 0.1 s; a miss when it went into the object
  // (no plate there), or when half a second after the reach's end it has not got there (something
  // stopped it early: felt before seen).
  void judge_touch(std::int64_t now_ns) {
    if (!feature_ || judged_ || !have_finger_) return;
    const Vec3 half = scene_.models[static_cast<std::size_t>(body_)].half_extents;
    const Vec3 p = body_pose().inverse() * finger_;  // the finger's centre, body frame
    const Vec3 rel = p - (touch_obj_ + offset_obj_);
    const double gap = rel.dot(normal_obj_) - finger_radius_;  // < 0: past the touched face's plane
    // Over the face (within its other axes' half extents), where the finger meets it or passes.
    const Vec3 face_half = half - half.cwiseProduct(normal_obj_.cwiseAbs());
    const bool over_face = ((p - normal_obj_ * p.dot(normal_obj_)).cwiseAbs() - face_half).maxCoeff() <= 0;
    const bool inside = ((p.cwiseAbs() - half).array() < finger_radius_ - miss_depth_).all();
    if (inside || (over_face && gap < -miss_depth_))
      return judge(false, arrived_ns_ >= 0 ? arrived_ns_ : now_ns,
                   "passed through the virtual surface (no plate there)");
    if (over_face && gap <= 0.001) {
      if (arrived_ns_ < 0) arrived_ns_ = now_ns;
      if (now_ns - arrived_ns_ >= 100'000'000) return judge(true, arrived_ns_, "");
    } else if (arrived_ns_ >= 0 && gap > 0.003) {
      arrived_ns_ = -1;  // it came off again before resting
    }
    if (now_ns >= reach_end_ns_ + 500'000'000)
      judge(false, now_ns, "stopped " + std::to_string(gap * 1e3) + " mm short of the surface");
  }

  void judge(bool hit, std::int64_t at_ns, const std::string& why) {
    judged_ = true;
    (hit ? hits_ : misses_)++;
    if (!hit) log("contact " + std::to_string(contact_) + " (" + feature_->name + "): a miss, the finger " + why);
    event(hit ? msg::USER_TOUCH : msg::USER_MISS, at_ns);
  }

  void event(msg::UserEventKind kind, std::int64_t stamp_ns, double force = 0) {
    fill_header(event_msg_.header(), stamp_ns, event_seq_++, "base");
    event_msg_.kind(kind);
    event_msg_.contact(static_cast<std::uint32_t>(contact_));
    event_msg_.feature(feature_ ? feature_->name : std::string());
    event_msg_.body(feature_ ? scene_.models[static_cast<std::size_t>(body_)].name : std::string());
    msgs::to_msg(feature_ ? surface_point() : Vec3::Zero(), event_msg_.point());
    msgs::to_msg(feature_ ? surface_normal() : Vec3::Zero(), event_msg_.normal());
    event_msg_.force(force);
    events_out_.write(event_msg_);
  }

  // parameters and the scene
  std::string scene_path_;
  haptics::Scene scene_;
  std::vector<UserAction> actions_;
  double hand_k_ = 500, finger_radius_ = 0.01, press_ = 0.004, miss_depth_ = 0.003;
  bool stop_when_done_ = false;
  // what the user sees and feels
  std::vector<Eigen::Isometry3d> base_T_obj_;
  Vec3 finger_ = Vec3::Zero();
  bool have_finger_ = false;
  // the script
  std::size_t index_ = 0;
  std::int64_t action_start_ns_ = 0;
  bool begun_ = false;
  double duration_ = 0;
  Vec3 target_ = Vec3::Zero(), action_from_ = Vec3::Zero();
  Eigen::Quaterniond hand_q_ = pointing(-Vec3::UnitX()), q_from_ = hand_q_;  // the user faces the robot
  // the current contact
  const haptics::DisplayFeature* feature_ = nullptr;
  int body_ = 0;
  Vec3 touch_obj_ = Vec3::Zero(), normal_obj_ = Vec3::UnitZ(), offset_obj_ = Vec3::Zero(), offset_from_ = Vec3::Zero();
  double force_ = 0, force_from_ = 0;
  ReachPath reach_;
  std::int64_t arrived_ns_ = -1, reach_end_ns_ = 0;
  bool judged_ = true, done_ = false;
  int contact_ = 0, hits_ = 0, misses_ = 0;
  std::uint64_t seq_ = 0, event_seq_ = 0;
  // messages and ports
  msg::ObjectState object_msg_;
  msg::PoseStamped hand_msg_, target_msg_;
  msg::UserEvent event_msg_;
  Input<msg::ObjectState> objects_in_;
  Input<msg::PoseStamped> hand_in_;
  Output<msg::PoseStamped> target_out_;
  Output<msg::UserEvent> events_out_;
};

}  // namespace wysiwyf::display

WYSIWYF_COMPONENT(wysiwyf::display::UserSim, "user_sim")
