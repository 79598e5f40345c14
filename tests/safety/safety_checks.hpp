#pragma once
// The safety campaign's checks of one run, at every 1 ms sample, from the truth (the simulated
// fingertip and the arm's measured joints), not from what the planner believed:
// - speed and separation (ISO/TS 15066 5.5.4) for every part of the arm while the display moves
//   it on its own (idle and surface modes; in admittance the user holds the plate): the speed at
//   which a part closes on the fingertip against the largest speed whose protective distance fits
//   the separation, from the standard's formula evaluated here (not the planner's code);
// - in a fault, the arm braking: no part closing on the hand faster than when the fault came;
// - the force on the hand within ISO/TS 15066 Annex A's limits for the hand and fingers
//   (140 N quasi-static, twice that for a transient contact shorter than 0.5 s);
// - the arm's joints within their URDF speeds, and the setpoint never faster than the arm's
//   safety gate allows (2 m/s);
// - every mode switch bumpless: the first setpoint step after it, less the new source's own motion
//   (the step after that), at most the supervisor's 0.1 mm (a switch to fault holds where the arm
//   is measured, not where it was sent: it is checked by its braking).
#include <string>
#include <vector>

#include "../display/loop_run.hpp"
#include "arm_model/arm_model.hpp"

namespace wysiwyf::safety {

// ISO/TS 15066's protective separation distance and the values the display is specified with.
struct SafetyLimits {
  double human_speed = 1.6;           // v_h, m/s
  double reaction_time = 0.1;         // T_r, s
  double braking_deceleration = 1.5;  // a_s, m/s^2
  double intrusion = 0.0;             // C, m
  double human_uncertainty = 0.0;     // Z_d, m: none, the check knows where the hand is (the planner's
                                      // Z_d is its allowance for its tracker's error)
  double robot_uncertainty = 0.01;    // Z_r, m
  double finger_radius = 0.01;        // m around the tracked fingertip point
  double touching = 0.003;            // m: a fingertip this near the plate or knob touches the tool; the
                                      // tool's parts are then in contact by design (the force limits apply)
  double ssm_tolerance = 0.005;       // m/s: the simulated arm's joint-velocity noise
  double quasi_static_force = 140.0;  // N, hand and fingers (ISO/TS 15066 Table A.2)
  double transient_force = 280.0;     // N, twice the quasi-static limit
  double transient_s = 0.5;           // s a contact above the quasi-static limit may last
  double tool_mass = 1.1563;          // kg the wrist sensor carries (its weight is not the hand's force)
  double setpoint_speed = 2.0;        // m/s (the safety gate's max_setpoint_speed)
  double switch_step = 1e-4;          // m around a mode switch

  // S_p(v_r): the protective separation distance for a robot approaching at v_r.
  double protective_distance(double v_r) const;
  // The largest v_r whose S_p fits the separation (bisection on S_p; 0 if none).
  double allowed_speed(double separation) const;
};

struct Violation {
  std::string check;  // "separation", "fault_braking", "force", "joint_speed", "setpoint_speed", "switch_step",
                      // "run"
  double t = 0;       // s
  double value = 0, limit = 0;
  std::string detail;
};

struct RunFigures {
  int samples = 0;
  double worst_approach_excess = -1e9;  // m/s over the allowed speed (<= 0: never faster)
  std::string worst_part;
  double worst_t = 0;
  double min_separation = 1e9;       // m, any part, in idle and surface modes
  double min_link_separation = 1e9;  // m, parts other than the tool (plate, knob, sensor), any mode
  double max_force = 0;              // N on the hand
  double max_joint_speed_ratio = 0;  // of the URDF limit
  double max_setpoint_speed = 0;     // m/s
  double max_switch_step = 0;        // m
  int touches = 0, misses = 0, switches = 0;
  std::vector<Violation> violations;  // the first of each check
};

// The checks over a run of the loop on `model`'s arm.
RunFigures check_run(const test::LoopRun& run, const robot::ArmModel& model, const SafetyLimits& limits = {});

}  // namespace wysiwyf::safety
