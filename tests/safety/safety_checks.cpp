#include "safety_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "arm_clearance/arm_clearance.hpp"

namespace wysiwyf::safety {

namespace {

constexpr int kAdmittance = 2, kFault = 3;  // DisplayModeKind
constexpr int kTouch = 1, kMiss = 2;

// The tool the user touches (sensor, plate, knob, its lamps): in contact by design.
bool is_tool(const std::string& part) {
  const std::string link = part.substr(0, part.find(' '));
  return link == "dev" || link == "knob" || link == "ft_sensor" || link == "plate" || link.rfind("marker", 0) == 0 ||
         link.rfind("lamp", 0) == 0;
}

void note(RunFigures& f, const std::string& check, double t, double value, double limit, const std::string& detail) {
  for (const auto& v : f.violations)
    if (v.check == check) return;  // the first of each check is the one to replay
  f.violations.push_back({check, t, value, limit, detail});
}

std::string mm(double m) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f mm", m * 1e3);
  return b;
}

}  // namespace

double SafetyLimits::protective_distance(double v_r) const {
  const double stop_time = v_r / braking_deceleration;
  const double s_h = human_speed * (reaction_time + stop_time);  // the person, while the robot reacts and stops
  const double s_r = v_r * reaction_time;                        // the robot, while it reacts
  const double s_s = v_r * v_r / (2 * braking_deceleration);     // the robot, while it stops
  return s_h + s_r + s_s + intrusion + human_uncertainty + robot_uncertainty;
}

double SafetyLimits::allowed_speed(double separation) const {
  if (protective_distance(0) > separation) return 0;
  double lo = 0, hi = 10;  // m/s: S_p is increasing in v_r
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (protective_distance(mid) <= separation ? lo : hi) = mid;
  }
  return lo;
}

RunFigures check_run(const test::LoopRun& run, const robot::ArmModel& model, const SafetyLimits& limits) {
  RunFigures f;
  if (!run.result.ok) note(f, "run", 0, 0, 0, "the run failed: " + run.result.error);
  const robot::ArmClearance clearance(model);
  std::vector<bool> tool(clearance.parts());
  std::vector<bool> contact(clearance.parts());  // the surfaces a user touches: the plate and its knob
  for (std::size_t i = 0; i < tool.size(); ++i) {
    const std::string& name = clearance.part_name(i);
    tool[i] = is_tool(name);
    contact[i] = name.rfind("dev ", 0) == 0 || name.rfind("knob ", 0) == 0;
  }
  const robot::JointVector& vmax = model.limits().velocity;
  double above_since = -1;   // s the hand force went above the quasi-static limit (-1: below)
  double fault_closing = 0;  // m/s: the fastest approach when the last fault came
  for (std::size_t i = 0; i < run.ticks.size(); ++i) {
    const test::Tick& k = run.ticks[i];
    ++f.samples;
    const auto& parts = clearance.evaluate(k.q, k.qd, k.hand);
    double closing = 0;  // the fastest part's approach
    bool touching = false;
    for (std::size_t p = 0; p < parts.size(); ++p)
      touching = touching || (contact[p] && parts[p].distance - limits.finger_radius <= limits.touching);
    for (std::size_t p = 0; p < parts.size(); ++p) {
      const double s = std::max(0.0, parts[p].distance - limits.finger_radius);
      if (!tool[p]) f.min_link_separation = std::min(f.min_link_separation, s);
      closing = std::max(closing, parts[p].approach_speed);
      if (k.mode == kAdmittance || k.mode == kFault) continue;  // the user's motion; braking (below)
      if (touching && tool[p]) continue;                        // contact by design
      f.min_separation = std::min(f.min_separation, s);
      const double excess = parts[p].approach_speed - limits.allowed_speed(s);
      if (excess > f.worst_approach_excess)
        f.worst_approach_excess = excess, f.worst_part = parts[p].name, f.worst_t = k.t;
      if (excess > limits.ssm_tolerance)
        note(f, "separation", k.t, parts[p].approach_speed, limits.allowed_speed(s) + limits.ssm_tolerance,
             std::string("the ") + parts[p].name + " closed on the hand at " + std::to_string(parts[p].approach_speed) +
                 " m/s at " + mm(s));
    }
    // A fault brakes the arm from where it was: no part may close on the hand faster than at the fault.
    if (k.mode == kFault && (i == 0 || run.ticks[i - 1].mode != kFault)) fault_closing = closing;
    if (k.mode == kFault && closing > fault_closing + limits.ssm_tolerance)
      note(f, "fault_braking", k.t, closing, fault_closing + limits.ssm_tolerance,
           "a part closed on the hand faster than when the fault came");
    const double force = test::user_force(k, limits.tool_mass);
    f.max_force = std::max(f.max_force, force);
    if (force > limits.quasi_static_force) {
      if (above_since < 0) above_since = k.t;
      if (k.t - above_since > limits.transient_s)
        note(f, "force", k.t, force, limits.quasi_static_force,
             "above the quasi-static limit for " + std::to_string(k.t - above_since) + " s");
    } else {
      above_since = -1;
    }
    if (force > limits.transient_force)
      note(f, "force", k.t, force, limits.transient_force, "above the transient limit");
    for (int j = 0; j < model.dof(); ++j) {
      const double ratio = std::abs(k.qd[j]) / vmax[j];
      f.max_joint_speed_ratio = std::max(f.max_joint_speed_ratio, ratio);
      if (ratio > 1.0)
        note(f, "joint_speed", k.t, std::abs(k.qd[j]), vmax[j], "joint " + std::to_string(j + 1) + " beyond its limit");
    }
    if (i == 0) continue;
    const test::Tick& before = run.ticks[i - 1];
    const double dt = k.t - before.t;
    const bool switched = k.mode != before.mode && before.mode != 0;  // (0: before the supervisor's first setpoint)
    f.switches += switched;
    if (k.mode == kFault) continue;  // (a fault holds where the arm is, not where it was sent: no step check)
    if (dt > 0) {
      const double v = (k.setpoint - before.setpoint).norm() / dt;
      f.max_setpoint_speed = std::max(f.max_setpoint_speed, v);
      if (v > limits.setpoint_speed)
        note(f, "setpoint_speed", k.t, v, limits.setpoint_speed, "the setpoint stepped " + mm(v * dt));
    }
    if (switched) {
      // The supervisor holds until the new source continues from its last setpoint, then forwards
      // it: the first step after the switch less the source's own motion (the step after it).
      auto step_at = [&](std::size_t n) { return (run.ticks[n].setpoint - run.ticks[n - 1].setpoint).norm(); };
      std::size_t first = i;
      while (first + 1 < run.ticks.size() && first < i + 200 && step_at(first) < 1e-9) ++first;
      const double jump =
          first + 1 < run.ticks.size() ? std::max(0.0, step_at(first) - step_at(first + 1)) : step_at(first);
      f.max_switch_step = std::max(f.max_switch_step, jump);
      if (jump > limits.switch_step)
        note(f, "switch_step", k.t, jump, limits.switch_step,
             "a " + mm(jump) + " setpoint step at the switch to mode " + std::to_string(k.mode));
    }
  }
  for (const auto& e : run.events)
    if (e.what == "user") f.touches += e.kind == kTouch, f.misses += e.kind == kMiss;
  return f;
}

}  // namespace wysiwyf::safety
