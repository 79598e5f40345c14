#pragma once
// From Cartesian setpoints to the safety gate's joint targets, once per servo period: each
// setpoint (base_T_dev and its twist, at any period of 1 to 20 ms) is screened by the gate,
// tracked by the CartesianTracker, and the tracked pose's nearest IK solution becomes the gate's
// joint target. The same code runs in arm_sim and in puma_driver, so both arms are commanded
// identically, for any arm the ArmModel loads.
#include <cstdint>
#include <string>
#include <string_view>

#include "arm_model/arm_model.hpp"
#include "safety_gate/safety_gate.hpp"
#include "setpoint_following/cartesian_tracker.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot {

class SetpointFollower {
 public:
  // model: with its tip at the frame the setpoints place (tip_name), fixed to its last body; model
  // and gate (of the model's joint count) must outlive this. tracker_hz: natural frequency of the
  // tracker; dt: the servo period.
  SetpointFollower(const ArmModel& model, std::string tip_name, SafetyGate& gate, double tracker_hz, double dt);

  enum class Taken { kFollowed, kRefused, kFaulted };
  // A setpoint as it arrived. One whose stamp is stale (older than max_setpoint_age: a zero stamp),
  // from the future (beyond max_setpoint_lead) or older than the last followed one is refused
  // and changes nothing (refusal() says why): it does not feed the watchdog either. One for
  // another frame than base_T_<tip>, or one the gate refuses, faults the gate (an input fault).
  // `writer`: the process that sent it (Input::writer(): empty for this one), named by the gate
  // when the stream is lost.
  Taken take(const msg::CartesianSetpoint& setpoint, std::int64_t now_ns, std::string_view writer = {});
  const std::string& refusal() const { return refusal_; }
  // Every servo period, before SafetyGate::step(): advances the tracker and sets the gate's target.
  void update(std::int64_t now_ns);

  // The `source` field of the last accepted setpoint ("admittance", "surface", a script's name).
  const std::string& source() const { return source_; }

 private:
  double loss_timeout() const;  // s

  const ArmModel& model_;
  std::string tip_name_;
  SafetyGate& gate_;
  double omega_, dt_;
  CartesianTracker tracker_;
  bool have_target_ = false;
  JointVector q_target_;
  std::string source_, refusal_;
  std::int64_t last_stamp_ns_ = 0;  // of the last followed setpoint, while following
};

}  // namespace wysiwyf::robot
