#pragma once
// From Cartesian setpoints to the safety gate's joint targets, once per servo period: each
// setpoint (base_T_dev and its twist, at any period of 1 to 20 ms) is screened by the gate,
// tracked by the CartesianTracker, and the tracked pose's nearest IK solution becomes the gate's
// joint target. The same code runs in puma_sim and in puma_driver, so both arms are commanded
// identically.
#include <cstdint>
#include <string>

#include "puma_model/puma_model.hpp"
#include "safety_gate/safety_gate.hpp"
#include "setpoint_following/cartesian_tracker.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot {

class SetpointFollower {
 public:
  // model: with its tip at the frame the setpoints place (tip_name); model and gate must outlive
  // this. tracker_hz: natural frequency of the tracker; dt: the servo period.
  SetpointFollower(const PumaModel& model, std::string tip_name, SafetyGate& gate, double tracker_hz, double dt);

  // A setpoint as it arrived. One for another frame than base_T_<tip>, or one the gate refuses,
  // faults the gate.
  void take(const msg::CartesianSetpoint& setpoint, std::int64_t now_ns);
  // Every servo period, before SafetyGate::step(): advances the tracker and sets the gate's target.
  void update(std::int64_t now_ns);

  // The `source` field of the last accepted setpoint ("admittance", "surface", a script's name).
  const std::string& source() const { return source_; }

 private:
  const PumaModel& model_;
  std::string tip_name_;
  SafetyGate& gate_;
  double omega_, dt_;
  CartesianTracker tracker_;
  bool have_target_ = false;
  Vector6d q_target_ = Vector6d::Zero();
  std::string source_;
};

}  // namespace wysiwyf::robot
