#pragma once
// surface_planner: surface display mode (paper section 2.3). From the tracked hand it predicts
// which displayable feature of the virtual objects the hand is about to touch, and moves the
// plate there, square to the face and with its knob on the virtual knob, before the hand arrives:
//
//   hand (HandFilter: latency taken out, velocity) -> the path the hand will take (FeatureChooser:
//   the nearest feature, with hysteresis) -> the plate poses that display it (placement: four
//   turns about the face normal, the one the arm reaches along the path on its IK branch, within
//   limits) -> a path through the virtual object's inside (PlatePath: back into the object behind
//   the face the plate is on, across, out through the target face: never through the space the
//   hand comes from) -> progress along it at the speed speed and separation monitoring allows.
//
// Speed and separation monitoring (ISO/TS 15066, SeparationMonitor): every tick, the path speed is
// the largest at which no part of the arm approaches the hand faster than the protective distance
// allows; within it an approaching motion stops (WAITING). Without a tracked hand the arm moves at
// speed_without_hand at most.
//
// Outside surface mode (the supervisor's DisplayMode) it follows what the arm was last commanded
// (robot/setpoint), so that when surface mode comes back it starts from there, without a step.
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <set>
#include <memory>

#include "arm_clearance/arm_clearance.hpp"
#include "arm_model/display_frames.hpp"
#include "feature_choice.hpp"
#include "hand_filter.hpp"
#include "placement.hpp"
#include "plate_path.hpp"
#include "separation_monitor.hpp"
#include "scene/scene.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/joint_positions.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::display {

using Vec3 = Eigen::Vector3d;

inline double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

class SurfacePlanner final : public Component {
 public:
  // Parameters, ports, the scene and the arm model.
  void configure(Context& ctx) override;

  // The hand filter anew; the objects where the scene places them.
  void activate() override;

  // One planning step: inputs, the target, the path rate (SSM), the setpoint and the status.
  void tick(Time now) override;

 private:
  // Takes every input; non-finite ones are rejected; the hand goes into its filter.
  void read_inputs(std::int64_t now_ns);

  // The feature the hand goes for; a new one (or its object moved) gets a new path.
  void choose_target(const Vec3& hand, std::int64_t now_ns);

  // The plate is moving along its path (faster than 2 mm/s).
  bool moving() const { return !path_.done() && kappa_ * path_.velocity().norm() > 0.002; }

  // A path from the commanded pose to a plate pose displaying `f`, through the object's inside.
  void plan(const haptics::DisplayFeature& f, const Eigen::Isometry3d& base_T_obj);

  // The status: idle, moving, waiting (SSM), in place, unreachable; ETA and the hand's.
  void report(std::int64_t now_ns, bool hand_known, const Vec3& hand, double ssm);

  // A fault: stop the path, say why.
  void fault(std::int64_t now_ns, const std::string& why);

  // The setpoint: the commanded pose and its velocity.
  void publish(std::int64_t now_ns, const Vec3& v, const Vec3& w);

  // The status as it stands.
  void publish_status(std::int64_t now_ns);

  // parameters and models
  std::string scene_path_, urdf_;
  haptics::Scene scene_;
  std::unique_ptr<robot::ArmModel> model_;
  std::unique_ptr<robot::ArmClearance> clearance_;
  std::unique_ptr<SeparationMonitor> monitor_;
  std::unique_ptr<FeatureChooser> chooser_;
  robot::SsmParams ssm_;
  PathLimits limits_;
  double inner_depth_ = 0.05, accel_density_ = 20, settle_time_ = 0.1, ssm_margin_ = 0.9;
  double finger_radius_ = 0.01, speed_without_hand_ = 0.25, in_place_ = 0.001, still_speed_ = 0.002, dt_ = 1e-3;
  std::int64_t hand_timeout_ns_ = 0, hand_max_lead_ns_ = 0, input_timeout_ns_ = 0;
  // what it knows
  HandFilter hand_;
  std::vector<Eigen::Isometry3d> base_T_obj_;
  robot::JointVector q_;
  Eigen::Isometry3d device_ = Eigen::Isometry3d::Identity(), commanded_ = Eigen::Isometry3d::Identity();
  bool have_joints_ = false, have_device_ = false, have_commanded_ = false;
  std::int64_t joints_ns_ = 0, device_ns_ = 0;
  double device_speed_ = 0;
  std::deque<std::pair<std::int64_t, Vec3>> device_history_;
  msg::DisplayModeKind mode_ = msg::MODE_IDLE;
  // the plan
  Eigen::Isometry3d cmd_ = Eigen::Isometry3d::Identity(), target_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d planned_obj_ = Eigen::Isometry3d::Identity();
  bool have_cmd_ = false, replan_ = false, was_in_place_ = false;
  const haptics::DisplayFeature* target_feature_ = nullptr;
  PlatePath path_;
  double kappa_ = 0;
  std::string unreachable_;
  std::map<const haptics::DisplayFeature*, Vec3> unreachable_at_;  // where its object was when found out of reach
  std::set<const haptics::DisplayFeature*> unreachable_set_;
  std::uint64_t seq_ = 0, setpoint_seq_ = 0;
  // messages and ports
  msg::HandPosition hand_msg_;
  msg::ObjectState object_msg_;
  msg::JointState joints_msg_;
  msg::PoseStamped device_msg_;
  msg::DisplayMode mode_msg_;
  msg::CartesianSetpoint commanded_msg_, setpoint_msg_;
  std::int64_t sensed_ns_ = 0;
  msg::PlannerStatus status_;
  Input<msg::HandPosition> hand_in_;
  Input<msg::ObjectState> objects_in_;
  Input<msg::JointState> joints_in_;
  Input<msg::PoseStamped> device_in_;
  Input<msg::DisplayMode> mode_in_;
  Input<msg::CartesianSetpoint> commanded_in_;
  Output<msg::CartesianSetpoint> setpoint_out_;
  Output<msg::PlannerStatus> status_out_;
};

}  // namespace wysiwyf::display
