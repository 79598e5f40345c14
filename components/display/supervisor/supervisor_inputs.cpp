// supervisor: its inputs taken and checked, and the recovery from the faults they cause.
#include "supervisor.hpp"

#include "wysiwyf/msg_checks.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace wysiwyf::display {

void Supervisor::read_inputs(std::int64_t now_ns) {
  take_setpoints(surface_in_, surface_, "surface", now_ns);
  take_setpoints(admittance_in_, admittance_, "admittance", now_ns);
  while (wrench_in_.take(wrench_msg_)) {
    if (const std::string why = problem(wrench_msg_); !why.empty()) {
      reject(wrench_in_, why);
      bad("the wrist reading: " + why, now_ns);
      continue;
    }
    wrench_ns_ = now_ns;
    reading_ = {msgs::to_eigen(wrench_msg_.wrench().force()), msgs::to_eigen(wrench_msg_.wrench().torque())};
    have_reading_ = true;
  }
  while (device_in_.take(device_msg_)) {
    if (const std::string why = problem(device_msg_); !why.empty()) {
      reject(device_in_, why);
      bad("the device pose: " + why, now_ns);
      continue;
    }
    device_ = msgs::to_isometry(device_msg_.pose()), have_device_ = true, device_ns_ = now_ns;
  }
  while (take_checked(hand_in_, hand_msg_)) {
    if (hand_msg_.status() == msg::TRACKING_LOST) continue;
    if (std::string why = msgs::frame_problem(hand_msg_.header(), "base"); !why.empty()) {
      reject(hand_in_, why);
      continue;
    }
    const Vec3 p = msgs::to_eigen(hand_msg_.position());
    hand_ = p, hand_ns_ = now_ns;
    const auto& c = hand_msg_.covariance();
    const double variance = std::max({c[0], c[4], c[8]});  // the largest axis, near enough
    hand_sigma_ = std::isfinite(variance) && variance > 0 ? std::sqrt(variance) : 0.0;
  }
  while (robot_in_.take(robot_msg_)) robot_ns_ = now_ns;
  while (planner_in_.take(planner_msg_)) planner_ns_ = now_ns;
  while (take_checked(objects_in_, object_msg_)) {
    base_T_obj_[object_msg_.child_frame_id().c_str()] = msgs::to_isometry(object_msg_.pose());
  }
}

void Supervisor::take_setpoints(Input<msg::CartesianSetpoint>& in, Stream& s, const char* source, std::int64_t now_ns) {
  s.fresh = false;
  while (in.take(setpoint_msg_)) {
    if (const std::string why = problem(setpoint_msg_); !why.empty()) {
      reject(in, why);
      bad(std::string("the ") + source + " setpoint: " + why, now_ns);
      continue;
    }
    if (std::string_view(setpoint_msg_.source().c_str()) != source) {
      reject(in, "source '" + std::string(setpoint_msg_.source().c_str()) + "', expected '" + source + "'");
      bad(std::string("a setpoint from '") + setpoint_msg_.source().c_str() + "' on the " + source + " input", now_ns);
      continue;
    }
    std::swap(s.sample, setpoint_msg_);
    s.at_ns = now_ns, s.fresh = true;
  }
}

// Stale inputs, the arm and the planner.
void Supervisor::check_inputs(std::int64_t now_ns) {
  if (mode_ == msg::MODE_IDLE) return;
  const Stream& source = mode_ == msg::MODE_SURFACE ? surface_ : admittance_;
  if (!taking_over_ && now_ns - source.at_ns > setpoint_timeout_ns_)
    return bad(std::string("no ") + mode_name(mode_) + " setpoint for " +
                   std::to_string(seconds(now_ns - source.at_ns)) + " s",
               now_ns);
  if (now_ns - wrench_ns_ > wrench_timeout_ns_)
    return bad("no wrist reading for " + std::to_string(seconds(now_ns - wrench_ns_)) + " s", now_ns);
  if (now_ns - robot_ns_ > status_timeout_ns_) return bad("no status from the arm", now_ns);
  if (robot_msg_.state() == msg::ARM_FAULT) return bad(std::string("the arm: ") + robot_msg_.reason().c_str(), now_ns);
  if (now_ns - planner_ns_ > status_timeout_ns_) return bad("no status from the surface planner", now_ns);
  if (planner_msg_.state() == msg::PLAN_FAULT)
    return bad(std::string("the surface planner: ") + planner_msg_.reason().c_str(), now_ns);
}

// Back to idle once every input has been good for recover_after. An arm held by a fault that
// bad input caused (a NaN, a jump: clearable) is asked to clear it once everything else is.
void Supervisor::recover(std::int64_t now_ns) {
  if (!auto_recover_) return;
  const bool arm_clearable = robot_ns_ >= 0 && robot_msg_.state() == msg::ARM_FAULT && robot_msg_.clearable();
  // (The planner's setpoint within setpoint_timeout, not this very tick: on the real clock the
  // planner ticks on a thread of its own, and some ticks find nothing new.)
  const bool good = surface_.at_ns >= 0 && now_ns - surface_.at_ns <= setpoint_timeout_ns_ &&
                    now_ns - wrench_ns_ <= wrench_timeout_ns_ && (robot_ok() || arm_clearable) &&
                    now_ns - planner_ns_ <= status_timeout_ns_ && planner_msg_.state() != msg::PLAN_FAULT;
  if (!good) {
    good_since_ns_ = -1;
    return;
  }
  if (good_since_ns_ < 0) good_since_ns_ = now_ns;
  if (now_ns - good_since_ns_ < recover_after_ns_) return;
  if (robot_ok()) return enter(msg::MODE_IDLE, now_ns, "inputs good again");
  if (now_ns - request_sent_ns_ >= kRequestRepeatNs) {  // until the arm says it has cleared it
    fill_header(request_msg_.header(), now_ns, request_seq_++, "base");
    request_msg_.request(msg::ARM_CLEAR_INPUT_FAULT);
    request_msg_.reason(("the display's inputs are good again after: " + reason_).substr(0, 127));
    arm_request_out_.write(request_msg_);
    request_sent_ns_ = now_ns;
  }
}

}  // namespace wysiwyf::display
