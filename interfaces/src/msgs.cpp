#include "wysiwyf/msgs.hpp"

#include <sstream>

#include "wysiwyf/idl/geometry_msgsPubSubTypes.h"
#include "wysiwyf/idl/sensor_msgsPubSubTypes.h"
#include "wysiwyf/idl/display_msgsPubSubTypes.h"
#include "wysiwyf/idl/wysiwyf_msgsPubSubTypes.h"
#include "wysiwyf/number_text.hpp"

WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, Image)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, CameraInfo)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, JointState)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, PoseStamped)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, PoseWithCovariance)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, WrenchStamped)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, CartesianSetpoint)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, ObjectState)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, DisplayMode)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, RobotStatus)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, MarkerObservation)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, HandPosition)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, Attachment)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, PlannerStatus)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, UserEvent)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, ContactReport)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, HapticRegistration)

namespace wysiwyf::msgs {

namespace {

// Accumulates "key: value" lines at an indentation level.
class Yaml {
 public:
  Yaml& key(const std::string& k) {
    line() << k << ":\n";
    return *this;
  }
  template <class V>
  Yaml& kv(const std::string& k, const V& v) {
    line() << k << ": " << v << "\n";
    return *this;
  }
  Yaml& kv(const std::string& k, double v) {
    line() << k << ": " << num(v) << "\n";
    return *this;
  }
  template <class S>  // std::string or a bounded fixed_string
  Yaml& str(const std::string& k, const S& v) {
    line() << k << ": \"" << v.c_str() << "\"\n";
    return *this;
  }
  template <class It>
  Yaml& list(const std::string& k, It begin, It end) {
    line() << k << ": [";
    for (It i = begin; i != end; ++i) out_ << (i == begin ? "" : ", ") << num(*i);
    out_ << "]\n";
    return *this;
  }
  Yaml& in() {
    ++depth_;
    return *this;
  }
  Yaml& out() {
    --depth_;
    return *this;
  }
  std::string text() const { return out_.str(); }

  static std::string num(double v) { return round_trip_text(v); }

 private:
  std::ostream& line() { return out_ << std::string(2 * depth_, ' '); }
  std::ostringstream out_;
  int depth_ = 0;
};

void header(Yaml& y, const std_msgs::Header& h) {
  y.key("header").in().kv("stamp_ns", h.stamp_ns()).kv("seq", h.seq()).str("frame_id", h.frame_id()).out();
}
void vec3(Yaml& y, const std::string& k, double x, double yy, double z) {
  y.key(k).in().kv("x", x).kv("y", yy).kv("z", z).out();
}
void pose(Yaml& y, const geometry_msgs::Pose& p) {
  y.key("pose").in();
  vec3(y, "position", p.position().x(), p.position().y(), p.position().z());
  const auto& q = p.orientation();
  y.key("orientation").in().kv("x", q.x()).kv("y", q.y()).kv("z", q.z()).kv("w", q.w()).out();
  y.out();
}
void twist(Yaml& y, const geometry_msgs::Twist& t) {
  y.key("twist").in();
  vec3(y, "linear", t.linear().x(), t.linear().y(), t.linear().z());
  vec3(y, "angular", t.angular().x(), t.angular().y(), t.angular().z());
  y.out();
}

const char* state_name(kernel_msgs::ComponentState s) {
  switch (s) {
    case kernel_msgs::STATE_CONFIGURED: return "configured";
    case kernel_msgs::STATE_ACTIVE: return "active";
    case kernel_msgs::STATE_STOPPED: return "stopped";
    case kernel_msgs::STATE_FAULT: return "fault";
    case kernel_msgs::STATE_HOLDING: return "holding";
  }
  return "?";
}
const char* contact_name(msg::ContactKind k) {
  switch (k) {
    case msg::CONTACT_RESTING: return "resting";
    case msg::CONTACT_COLLIDING: return "colliding";
    case msg::CONTACT_SEPARATING: return "separating";
  }
  return "?";
}
const char* mode_name(msg::DisplayModeKind k) {
  switch (k) {
    case msg::MODE_IDLE: return "idle";
    case msg::MODE_SURFACE: return "surface";
    case msg::MODE_ADMITTANCE: return "admittance";
    case msg::MODE_FAULT: return "fault";
  }
  return "?";
}

const char* arm_state_name(msg::ArmState s) {
  switch (s) {
    case msg::ARM_OK: return "ok";
    case msg::ARM_HOLDING: return "holding";
    case msg::ARM_FAULT: return "fault";
  }
  return "?";
}

const char* tracking_name(msg::TrackingStatus s) {
  switch (s) {
    case msg::TRACKING_LOST: return "lost";
    case msg::TRACKING_OK: return "tracking";
    case msg::TRACKING_COASTING: return "coasting";
  }
  return "?";
}

const char* planner_state_name(msg::PlannerState s) {
  switch (s) {
    case msg::PLAN_IDLE: return "idle";
    case msg::PLAN_MOVING: return "moving";
    case msg::PLAN_IN_PLACE: return "in_place";
    case msg::PLAN_WAITING: return "waiting";
    case msg::PLAN_UNREACHABLE: return "unreachable";
    case msg::PLAN_FAULT: return "fault";
  }
  return "?";
}

const char* user_event_name(msg::UserEventKind k) {
  switch (k) {
    case msg::USER_REACH: return "reach";
    case msg::USER_TOUCH: return "touch";
    case msg::USER_MISS: return "miss";
    case msg::USER_PUSH: return "push";
    case msg::USER_RELEASE: return "release";
    case msg::USER_WITHDRAW: return "withdraw";
    case msg::USER_DONE: return "done";
  }
  return "?";
}

}  // namespace

std::string to_yaml(const kernel_msgs::Diagnostics& m) {
  Yaml y;
  header(y, m.header());
  y.str("instance", m.instance()).str("type", m.type()).str("process", m.process()).kv("state", state_name(m.state()));
  y.kv("rate_hz", m.rate_hz()).kv("tick_rate_hz", m.tick_rate_hz()).kv("tick_time_p50_us", m.tick_time_p50_us());
  y.kv("tick_time_p99_us", m.tick_time_p99_us()).kv("tick_time_max_us", m.tick_time_max_us());
  y.kv("tick_late_p50_us", m.tick_late_p50_us()).kv("tick_late_p99_us", m.tick_late_p99_us());
  y.kv("tick_late_max_us", m.tick_late_max_us());
  y.kv("ticks", m.ticks()).kv("overruns", m.overruns()).kv("dropped_samples", m.dropped_samples());
  if (m.dropped_by_port().empty()) {
    y.kv("dropped_by_port", "{}");
  } else {
    y.key("dropped_by_port").in();
    for (const auto& p : m.dropped_by_port()) y.kv(p.port().to_string(), p.count());
    y.out();
  }
  y.kv("rejected_samples", m.rejected_samples()).kv("warnings", m.warnings()).str("last_warning", m.last_warning());
  y.str("last_error", m.last_error());
  return y.text();
}

std::string to_yaml(const msg::Image& m) {
  Yaml y;
  header(y, m.header());
  y.kv("height", m.height()).kv("width", m.width()).str("encoding", m.encoding());
  y.kv("is_bigendian", static_cast<int>(m.is_bigendian())).kv("step", m.step());
  std::uint64_t sum = 0;
  for (auto b : m.data()) sum += b;
  y.kv("data", "<" + std::to_string(m.data().size()) + " bytes, mean " +
                   Yaml::num(m.data().empty() ? 0.0 : static_cast<double>(sum) / m.data().size()) + ">");
  return y.text();
}

std::string to_yaml(const msg::CameraInfo& m) {
  Yaml y;
  header(y, m.header());
  y.kv("height", m.height()).kv("width", m.width()).str("distortion_model", m.distortion_model());
  y.list("d", m.d().begin(), m.d().end()).list("k", m.k().begin(), m.k().end());
  y.list("r", m.r().begin(), m.r().end()).list("p", m.p().begin(), m.p().end());
  return y.text();
}

std::string to_yaml(const msg::JointState& m) {
  Yaml y;
  header(y, m.header());
  y.list("position", m.position().begin(), m.position().end());
  y.list("velocity", m.velocity().begin(), m.velocity().end());
  y.list("effort", m.effort().begin(), m.effort().end());
  return y.text();
}

std::string to_yaml(const msg::PoseStamped& m) {
  Yaml y;
  header(y, m.header());
  y.str("child_frame_id", m.child_frame_id());
  pose(y, m.pose());
  return y.text();
}

std::string to_yaml(const msg::PoseWithCovariance& m) {
  Yaml y;
  header(y, m.header());
  y.str("child_frame_id", m.child_frame_id());
  pose(y, m.pose());
  y.list("covariance", m.covariance().begin(), m.covariance().end());
  return y.text();
}

std::string to_yaml(const msg::WrenchStamped& m) {
  Yaml y;
  header(y, m.header());
  const auto& w = m.wrench();
  y.key("wrench").in();
  vec3(y, "force", w.force().x(), w.force().y(), w.force().z());
  vec3(y, "torque", w.torque().x(), w.torque().y(), w.torque().z());
  y.out();
  return y.text();
}

std::string to_yaml(const msg::CartesianSetpoint& m) {
  Yaml y;
  header(y, m.header());
  y.str("child_frame_id", m.child_frame_id());
  pose(y, m.pose());
  twist(y, m.twist());
  y.str("source", m.source());
  y.kv("sensed_ns", m.sensed_ns());
  return y.text();
}

std::string to_yaml(const msg::ObjectState& m) {
  Yaml y;
  header(y, m.header());
  y.str("child_frame_id", m.child_frame_id());
  pose(y, m.pose());
  twist(y, m.twist());
  y.key("contacts");
  for (const auto& c : m.contacts()) {
    y.in().key("-").in();
    vec3(y, "position", c.position().x(), c.position().y(), c.position().z());
    vec3(y, "normal", c.normal().x(), c.normal().y(), c.normal().z());
    y.kv("gap", c.gap()).kv("force", c.force()).kv("kind", contact_name(c.kind())).str("other", c.other());
    y.out().out();
  }
  return y.text();
}

std::string to_yaml(const msg::DisplayMode& m) {
  Yaml y;
  header(y, m.header());
  y.kv("mode", mode_name(m.mode())).str("reason", m.reason());
  return y.text();
}

std::string to_yaml(const msg::RobotStatus& m) {
  Yaml y;
  header(y, m.header());
  y.kv("state", arm_state_name(m.state())).str("source", m.source()).str("reason", m.reason());
  return y.text();
}

std::string to_yaml(const msg::MarkerObservation& m) {
  Yaml y;
  header(y, m.header());
  y.kv("status", tracking_name(m.status())).kv("acquired", m.acquired() ? "true" : "false");
  y.kv("blobs", m.blobs()).kv("rejected", m.rejected());
  y.list("ids", m.ids().begin(), m.ids().end())
      .list("u", m.u().begin(), m.u().end())
      .list("v", m.v().begin(), m.v().end());
  y.kv("reprojection_rms", m.reprojection_rms()).kv("frames_without_fix", m.frames_without_fix());
  return y.text();
}

std::string to_yaml(const msg::HandPosition& m) {
  Yaml y;
  header(y, m.header());
  vec3(y, "position", m.position().x(), m.position().y(), m.position().z());
  y.list("covariance", m.covariance().begin(), m.covariance().end());
  y.kv("status", tracking_name(m.status())).str("source", m.source());
  return y.text();
}

std::string to_yaml(const msg::Attachment& m) {
  Yaml y;
  header(y, m.header());
  y.kv("attached", m.attached() ? "true" : "false").str("body", m.body()).str("feature", m.feature());
  y.key("obj_T_dev").in();
  pose(y, m.obj_T_dev());
  y.out();
  return y.text();
}

std::string to_yaml(const msg::PlannerStatus& m) {
  Yaml y;
  header(y, m.header());
  y.kv("state", planner_state_name(m.state())).str("feature", m.feature()).str("body", m.body());
  y.key("base_T_target").in();
  pose(y, m.base_T_target());
  y.out();
  y.kv("eta", m.eta()).kv("hand_eta", m.hand_eta()).kv("separation", m.separation());
  y.kv("speed_limit", m.speed_limit()).str("reason", m.reason());
  return y.text();
}

std::string to_yaml(const msg::UserEvent& m) {
  Yaml y;
  header(y, m.header());
  y.kv("kind", user_event_name(m.kind())).kv("contact", m.contact()).str("feature", m.feature()).str("body", m.body());
  vec3(y, "point", m.point().x(), m.point().y(), m.point().z());
  vec3(y, "normal", m.normal().x(), m.normal().y(), m.normal().z());
  y.kv("force", m.force());
  return y.text();
}

std::string to_yaml(const msg::ContactReport& m) {
  Yaml y;
  header(y, m.header());
  y.kv("contact", m.contact()).str("feature", m.feature()).kv("hit", m.hit() ? "true" : "false");
  y.kv("still_before_s", m.still_before_s()).kv("offset_mm", m.offset_mm()).kv("angle_deg", m.angle_deg());
  return y.text();
}

std::string to_yaml(const msg::HapticRegistration& m) {
  Yaml y;
  header(y, m.header());
  y.kv("contact", m.contact()).str("feature", m.feature()).kv("samples", m.samples());
  y.kv("p50_mm", m.p50_mm()).kv("p99_mm", m.p99_mm()).kv("max_mm", m.max_mm()).kv("max_deg", m.max_deg());
  y.kv("onset_max_mm", m.onset_max_mm()).kv("onset_max_deg", m.onset_max_deg());
  y.kv("peak_force_n", m.peak_force_n()).kv("push_force_n", m.push_force_n());
  return y.text();
}

const MessageRegistry& registry() {
  static const MessageRegistry r = [] {
    MessageRegistry reg;
    reg.add<kernel_msgs::Diagnostics>(&to_yaml);
    reg.add<msg::Image>(&to_yaml);
    reg.add<msg::CameraInfo>(&to_yaml);
    reg.add<msg::JointState>(&to_yaml);
    reg.add<msg::PoseStamped>(&to_yaml);
    reg.add<msg::PoseWithCovariance>(&to_yaml);
    reg.add<msg::WrenchStamped>(&to_yaml);
    reg.add<msg::CartesianSetpoint>(&to_yaml);
    reg.add<msg::ObjectState>(&to_yaml);
    reg.add<msg::DisplayMode>(&to_yaml);
    reg.add<msg::RobotStatus>(&to_yaml);
    reg.add<msg::MarkerObservation>(&to_yaml);
    reg.add<msg::HandPosition>(&to_yaml);
    reg.add<msg::Attachment>(&to_yaml);
    reg.add<msg::PlannerStatus>(&to_yaml);
    reg.add<msg::UserEvent>(&to_yaml);
    reg.add<msg::ContactReport>(&to_yaml);
    reg.add<msg::HapticRegistration>(&to_yaml);
    return reg;
  }();
  return r;
}

}  // namespace wysiwyf::msgs
