#pragma once
// Speed and separation monitoring (ISO/TS 15066:2016, 5.5.4): the protective separation distance
//   S_p = S_h + S_r + S_s + C + Z_d + Z_r
// with S_h = v_h (T_r + T_s) the person's approach while the robot reacts and stops, S_r = v_r T_r
// the robot's travel while it reacts, S_s = v_r^2 / (2 a_s) its braking distance (T_s = v_r / a_s),
// C the intrusion distance, Z_d and Z_r the position uncertainties of the person and the robot.
// The robot may approach at v_r only while the separation S stays at least S_p.
#include <algorithm>
#include <cmath>

namespace wysiwyf::robot {

struct SsmParams {
  double human_speed = 1.6;           // v_h, m/s: ISO 13855's walking/reaching speed, ISO/TS 15066 default
  double reaction_time = 0.1;         // T_r, s: sensing, planning and setpoint-to-motion latency
  double braking_deceleration = 1.5;  // a_s, m/s^2: the arm's assured deceleration along its path
  double intrusion = 0.0;             // C, m: reach of a body part past the sensing (0: the fingertip is tracked)
  double human_uncertainty = 0.02;    // Z_d, m: hand tracking error
  double robot_uncertainty = 0.01;    // Z_r, m: arm position error (following error, calibration)

  // S_p for a robot approach speed v_r.
  double protective_distance(double v_r) const {
    const double t_s = v_r / braking_deceleration;
    return human_speed * (reaction_time + t_s) + v_r * reaction_time + v_r * v_r / (2 * braking_deceleration) +
           intrusion + human_uncertainty + robot_uncertainty;
  }
  // The largest v_r with S_p(v_r) <= separation: 0 within the protective distance of a still robot.
  double allowed_speed(double separation) const {
    const double a = braking_deceleration;
    const double room = separation - human_speed * reaction_time - intrusion - human_uncertainty - robot_uncertainty;
    if (room <= 0) return 0.0;
    const double b = reaction_time + human_speed / a;  // v_r^2 / (2a) + b v_r - room = 0
    return a * (-b + std::sqrt(b * b + 2 * room / a));
  }
};

}  // namespace wysiwyf::robot
