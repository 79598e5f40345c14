// Test component: records the display loop at every tick into two files at deactivate, for the
// display tests to check against the truth (joint states, the true fingertip, the plate, the
// robot's setpoint, the modes, the planner's status, the user's events). Used by tests only.
// Columns of `samples`: t_ns, mode, planner_state, q0..5, qd0..5, hand xyz, plate xyz, plate
// quaternion xyzw, setpoint xyz, target xyz, target quaternion xyzw, separation, speed_limit,
// wrist force xyz, target feature, tracked hand xyz and status (the last HandPosition).
// Columns of `joints` (for arms of any joint count): t_ns, mode, hand xyz, n, q0..n-1, qd0..n-1.
#include <cstdio>
#include <fstream>

#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace {

using namespace wysiwyf;

class TestDisplayRecorder final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("display tests: records the loop at every tick");
    samples_path_ = ctx.param<std::string>("samples", "", "CSV of one row a tick");
    events_path_ = ctx.param<std::string>("events", "", "CSV of the user's events and the mode changes");
    joints_path_ = ctx.param<std::string>("joints", "", "CSV of every joint and the true hand, one row a tick");
    joints_ = ctx.input<msg::JointState>("joint_state", "", Qos::reliable(8));
    hand_ = ctx.input<msg::PoseStamped>("hand_pose", "", Qos::reliable(8));
    device_ = ctx.input<msg::PoseStamped>("device_pose", "", Qos::reliable(8));
    setpoint_ = ctx.input<msg::CartesianSetpoint>("setpoint", "", Qos::reliable(8));
    mode_ = ctx.input<msg::DisplayMode>("mode", "", Qos::reliable(64));
    planner_ = ctx.input<msg::PlannerStatus>("planner", "", Qos::reliable(64));
    events_ = ctx.input<msg::UserEvent>("events", "", Qos::reliable(64));
    wrench_ = ctx.input<msg::WrenchStamped>("wrench", "", Qos::reliable(8));
    tracked_ = ctx.input<msg::HandPosition>("tracked_hand", "", Qos::reliable(8));
  }

  void tick(Time now) override {
    while (joints_.take(j_)) {
    }
    while (hand_.take(h_)) {
    }
    while (device_.take(d_)) {
    }
    while (setpoint_.take(s_)) {
    }
    while (wrench_.take(w_)) {
    }
    while (tracked_.take(t_)) {
    }
    while (mode_.take(m_)) {
      if (m_.mode() != last_mode_) {
        char line[256];
        std::snprintf(line, sizeof line, "%lld,mode,%d,%s\n", static_cast<long long>(now.ns),
                      static_cast<int>(m_.mode()), m_.reason().c_str());
        event_text_ += line;
        last_mode_ = m_.mode();
      }
    }
    while (planner_.take(p_)) {
      std::string reason = p_.reason().c_str();
      for (auto& c : reason)
        if (c == ',') c = ';';
      // A new line when the state or the reason's words change (not its figures, every tick).
      const std::string words = reason.substr(0, reason.find_first_of("0123456789"));
      if (p_.state() != last_planner_ || words != last_reason_) {
        event_text_ +=
            std::to_string(now.ns) + ",planner," + std::to_string(static_cast<int>(p_.state())) + "," + reason + "\n";
        last_planner_ = p_.state(), last_reason_ = words;
      }
    }
    while (events_.take(e_)) {
      char line[512];
      std::snprintf(line, sizeof line, "%lld,user,%d,%u,%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                    static_cast<long long>(e_.header().stamp_ns()), static_cast<int>(e_.kind()), e_.contact(),
                    e_.feature().c_str(), e_.point().x(), e_.point().y(), e_.point().z(), e_.normal().x(),
                    e_.normal().y(), e_.normal().z());
      event_text_ += line;
    }
    const auto& q = j_.position();
    const auto& qd = j_.velocity();
    if (q.size() < 6 || qd.size() != q.size()) return;  // no joint state yet (rows hold six joints at least)
    const auto& hp = h_.pose().position();
    const auto& dp = d_.pose().position();
    const auto& dq = d_.pose().orientation();
    const auto& sp = s_.pose().position();
    const auto& tq = p_.base_T_target().orientation();
    const auto& tp = p_.base_T_target().position();
    const double values[] = {q[0],
                             q[1],
                             q[2],
                             q[3],
                             q[4],
                             q[5],
                             qd[0],
                             qd[1],
                             qd[2],
                             qd[3],
                             qd[4],
                             qd[5],
                             hp.x(),
                             hp.y(),
                             hp.z(),
                             dp.x(),
                             dp.y(),
                             dp.z(),
                             dq.x(),
                             dq.y(),
                             dq.z(),
                             dq.w(),
                             sp.x(),
                             sp.y(),
                             sp.z(),
                             tp.x(),
                             tp.y(),
                             tp.z(),
                             tq.x(),
                             tq.y(),
                             tq.z(),
                             tq.w(),
                             p_.separation(),
                             p_.speed_limit(),
                             w_.wrench().force().x(),
                             w_.wrench().force().y(),
                             w_.wrench().force().z()};
    char row[64];
    std::snprintf(row, sizeof row, "%lld,%d,%d", static_cast<long long>(now.ns), static_cast<int>(m_.mode()),
                  static_cast<int>(p_.state()));
    samples_text_ += row;
    for (double v : values) {
      std::snprintf(row, sizeof row, ",%.9g", v);
      samples_text_ += row;
    }
    samples_text_ += ",";
    samples_text_ += p_.feature().c_str();
    std::snprintf(row, sizeof row, ",%.9g,%.9g,%.9g,%d\n", t_.position().x(), t_.position().y(), t_.position().z(),
                  static_cast<int>(t_.status()));
    samples_text_ += row;
    if (!joints_path_.empty()) record_joints(now);
  }

  // One row of `joints`: every joint of the arm, whatever their number.
  void record_joints(Time now) {
    const auto& q = j_.position();
    const auto& qd = j_.velocity();
    char row[96];
    std::snprintf(row, sizeof row, "%lld,%d,%.9g,%.9g,%.9g,%zu", static_cast<long long>(now.ns),
                  static_cast<int>(m_.mode()), h_.pose().position().x(), h_.pose().position().y(),
                  h_.pose().position().z(), q.size());
    joints_text_ += row;
    for (double v : q) {
      std::snprintf(row, sizeof row, ",%.9g", v);
      joints_text_ += row;
    }
    for (std::size_t j = 0; j < q.size(); ++j) {
      std::snprintf(row, sizeof row, ",%.9g", j < qd.size() ? qd[j] : 0.0);
      joints_text_ += row;
    }
    joints_text_ += "\n";
  }

  void deactivate() override {
    if (!joints_path_.empty()) std::ofstream(joints_path_) << joints_text_;
    if (!samples_path_.empty()) std::ofstream(samples_path_) << samples_text_;
    if (!events_path_.empty()) std::ofstream(events_path_) << event_text_;
  }

 private:
  std::string samples_path_, events_path_, joints_path_, samples_text_, event_text_, joints_text_;
  msg::DisplayModeKind last_mode_ = msg::MODE_IDLE;
  msg::PlannerState last_planner_ = msg::PLAN_IDLE;
  std::string last_reason_;
  msg::JointState j_;
  msg::PoseStamped h_, d_;
  msg::CartesianSetpoint s_;
  msg::DisplayMode m_;
  msg::PlannerStatus p_;
  msg::UserEvent e_;
  msg::WrenchStamped w_;
  msg::HandPosition t_;
  Input<msg::HandPosition> tracked_;
  Input<msg::JointState> joints_;
  Input<msg::PoseStamped> hand_, device_;
  Input<msg::CartesianSetpoint> setpoint_;
  Input<msg::DisplayMode> mode_;
  Input<msg::PlannerStatus> planner_;
  Input<msg::UserEvent> events_;
  Input<msg::WrenchStamped> wrench_;
};

}  // namespace

WYSIWYF_COMPONENT(TestDisplayRecorder, "test_display_recorder")
