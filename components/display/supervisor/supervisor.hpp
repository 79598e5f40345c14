#pragma once
// supervisor: the display's modes (paper section 2.3) and the only writer of the robot's setpoint.
//
//   idle -> surface (the surface planner's setpoints) -> admittance on a touch (admittance_sim's)
//   -> surface on a release -> ...; fault (hold) on anything odd, back through idle once the
//   inputs are good again (auto_recover).
//
// A touch is the user's force (wrist reading less the tool's weight) above contact_force for
// contact_dwell with the tracked hand near the plate; a release is it below release_force for
// release_dwell with the hand leaving (ContactDetector). Switching is bumpless: entering
// admittance, admittance_sim is attached to the feature the planner chose at the pose the arm is
// commanded to (obj_T_dev = obj_T_base * base_T_dev), so its first setpoint is the last one the
// arm had; leaving, the planner has followed the commanded pose (it reads robot/setpoint), so it
// starts there. Either way the supervisor forwards the new source only once its setpoint is within
// max_switch_step of the last one it sent, and holds that meanwhile.
//
// Faults (held: the last pose again, zero twist, DisplayMode FAULT with the reason): a stale or
// non-finite input, a setpoint from another source than its port's, a setpoint that jumps faster
// than max_setpoint_speed, the arm, the planner or admittance_sim failing, a force on the plate
// with the hand far from it. An arm fault that bad input caused (RobotStatus.clearable: a NaN,
// a jump, its setpoint stream lost) is cleared by asking the arm (arm_request) once every other
// input is good again, idle or not: the arm follows again only through this normal start.
//
// The start: idle or held, while the arm follows nothing (it waits for its first setpoint, holds
// after a fault, or has said nothing for status_timeout), the supervisor's setpoint is the hold
// where the arm stands (its measured pose; nothing without a fresh one), so neither side's restart
// makes a step: a restarted arm parked elsewhere, or a restarted display whose physics and planner
// begin anew. Once the arm follows that hold, idle -> surface, the planner continuing from it.
#include <cstdint>
#include <map>
#include <string>

#include "contact_detector.hpp"
#include "scene/scene.hpp"
#include "scene/tool_load.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::display {

using Vec3 = Eigen::Vector3d;

inline double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }
inline std::int64_t nanos(double s) { return static_cast<std::int64_t>(s * 1e9); }

inline const char* mode_name(msg::DisplayModeKind m) {
  switch (m) {
    case msg::MODE_IDLE: return "idle";
    case msg::MODE_SURFACE: return "surface";
    case msg::MODE_ADMITTANCE: return "admittance";
    case msg::MODE_FAULT: return "fault";
  }
  return "?";
}

// A setpoint stream: the newest sample and when it came.
struct Stream {
  msg::CartesianSetpoint sample;
  std::int64_t at_ns = -1;
  bool fresh = false;  // arrived this tick
};

class Supervisor final : public Component {
 public:
  // Parameters, ports and the scene.
  void configure(Context& ctx) override;

  // Reads the inputs, checks them, runs the mode, sends the setpoint.
  void tick(Time now) override;

 private:
  // Takes every input; a non-finite one is rejected and, where it matters, a fault.
  void read_inputs(std::int64_t now_ns);

  // A source's setpoints: finite and from that source, else a fault.
  void take_setpoints(Input<msg::CartesianSetpoint>& in, Stream& s, const char* source, std::int64_t now_ns);

  // Stale inputs, the arm and the planner.
  void check_inputs(std::int64_t now_ns);

  // The arm's status is known and not a fault.
  bool robot_ok() const { return robot_ns_ >= 0 && robot_msg_.state() != msg::ARM_FAULT; }
  // The arm says it follows the setpoints (status fresh and ok).
  bool arm_follows(std::int64_t now_ns) const {
    return robot_ns_ >= 0 && now_ns - robot_ns_ <= status_timeout_ns_ && robot_msg_.state() == msg::ARM_OK;
  }

  // Idle or held: while the arm follows nothing, the hold is its measured pose, at rest; without a
  // fresh measurement nothing is sent (a killed arm's last pose is no hold for its successor).
  void hold_where_the_arm_stands(std::int64_t now_ns);
  // A source's setpoint continues from the last one sent (within max_switch_step).
  bool near(const Stream& s) const {
    return (msgs::to_eigen(s.sample.pose().position()) - msgs::to_eigen(out_.pose().position())).norm() <=
           max_switch_step_;
  }

  // Forwards a source's setpoint; one that jumps too fast is a fault.
  void forward(const Stream& s);

  // A new source takes over once it continues from the last setpoint.
  void take_over(const Stream& s, std::int64_t now_ns);

  // Touch and release from the user's force and the hand (ContactDetector).
  void watch_contact(std::int64_t now_ns);

  // m from the hand point to the plate, less the finger's radius.
  double plate_distance(const Vec3& hand) const;

  // The device holds the planner's feature where the arm is commanded to be.
  void attach(std::int64_t now_ns);

  // Lets go of the held object, if any.
  void detach(std::int64_t now_ns);

  // A body's pose as the scene file places it (before the first ObjectState).
  Eigen::Isometry3d initial_pose(const std::string& body) const;

  // Switches mode (logged, reported), the new source to take over bumplessly.
  void enter(msg::DisplayModeKind mode, std::int64_t now_ns, const std::string& why);

  // Something is wrong: hold where the arm was sent, let go of the object, and say why.
  void bad(const std::string& why, std::int64_t now_ns);

  // Back to idle once every input has been good for recover_after. An arm held by a fault that
  // bad input caused (a NaN, a jump: clearable) is asked to clear it once everything else is.
  void recover(std::int64_t now_ns);

  // The setpoint, labelled with what it follows.
  void publish_setpoint(std::int64_t now_ns);

  // The mode and why (also every 100 ms).
  void publish_mode(std::int64_t now_ns);

  // parameters
  std::string scene_path_;
  haptics::Scene scene_;
  ContactDetector detector_;
  double finger_radius_ = 0.01, max_switch_step_ = 1e-4, max_speed_ = 2;
  std::int64_t switch_timeout_ns_ = 0, setpoint_timeout_ns_ = 0, wrench_timeout_ns_ = 0, status_timeout_ns_ = 0;
  bool auto_recover_ = true;
  std::int64_t recover_after_ns_ = 0;
  static constexpr std::int64_t kRequestRepeatNs = 100'000'000;  // while the arm has not cleared
  std::int64_t request_sent_ns_ = -kRequestRepeatNs;
  std::uint64_t request_seq_ = 0;
  msg::ArmRequest request_msg_;
  // inputs
  Stream surface_, admittance_;
  haptics::SensorReading reading_;
  bool have_reading_ = false, have_device_ = false;
  Eigen::Isometry3d device_ = Eigen::Isometry3d::Identity();
  Vec3 hand_ = Vec3::Zero();
  double hand_sigma_ = 0;  // m, the tracker's stated uncertainty
  std::int64_t wrench_ns_ = -1, hand_ns_ = -1, robot_ns_ = -1, planner_ns_ = -1, device_ns_ = -1;
  std::map<std::string, Eigen::Isometry3d> base_T_obj_;
  // the mode
  msg::DisplayModeKind mode_ = msg::MODE_IDLE;
  std::string reason_ = "starting";
  std::int64_t switched_ns_ = 0, good_since_ns_ = -1, mode_sent_ns_ = -1'000'000'000;
  bool taking_over_ = false, sent_ = false, attached_ = false;
  bool hold_unknown_ = false;  // the arm follows nothing and its pose is not known: send nothing
  std::uint64_t out_seq_ = 0, mode_seq_ = 0, attach_seq_ = 0;
  // messages and ports
  msg::CartesianSetpoint setpoint_msg_, out_;
  msg::WrenchStamped wrench_msg_;
  msg::PoseStamped device_msg_;
  msg::HandPosition hand_msg_;
  msg::RobotStatus robot_msg_;
  msg::PlannerStatus planner_msg_;
  msg::ObjectState object_msg_;
  msg::DisplayMode mode_msg_;
  msg::Attachment attach_msg_;
  Input<msg::CartesianSetpoint> surface_in_, admittance_in_;
  Input<msg::WrenchStamped> wrench_in_;
  Input<msg::PoseStamped> device_in_;
  Input<msg::HandPosition> hand_in_;
  Input<msg::RobotStatus> robot_in_;
  Input<msg::PlannerStatus> planner_in_;
  Input<msg::ObjectState> objects_in_;
  Output<msg::CartesianSetpoint> setpoint_out_;
  Output<msg::DisplayMode> mode_out_;
  Output<msg::Attachment> attach_out_;
  Output<msg::ArmRequest> arm_request_out_;
};

}  // namespace wysiwyf::display
