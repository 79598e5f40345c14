#include "arm_interface/gate_params.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace wysiwyf::robot {

SafetyConfig declare_gate_params(Context& ctx) {
  SafetyConfig c;
  const auto accel = ctx.param<std::vector<double>>(
      "acceleration_limits", {8, 8, 10, 30, 30, 30},
      "hard joint acceleration limits, rad/s^2 (the URDF has none); the reference uses acceleration_fraction of them",
      Range{0.01, 1000});
  c.velocity_fraction = ctx.param<double>(
      "velocity_fraction", 0.9, "share of the URDF velocity limits the reference may use (the rest is servo margin)",
      Range{0.05, 1});
  c.acceleration_fraction = ctx.param<double>("acceleration_fraction", 0.8,
                                              "share of acceleration_limits the reference may use", Range{0.05, 1});
  c.position_margin = ctx.param<double>(
      "position_margin", 0.02, "rad kept between the reference and every joint position limit", Range{0, 0.5});
  c.approach_rate = ctx.param<double>(
      "approach_rate", 50.0, "1/s, first-order rate at which the reference closes the last bit of a move", Range{1, 2000});
  c.setpoint_timeout = ctx.param<double>(
      "setpoint_timeout", 0.06, "s without a setpoint before braking to a hold (3 periods of a 20 ms stream)",
      Range{0.002, 10});
  c.max_setpoint_step = ctx.param<double>(
      "max_setpoint_step", 0.1, "m a setpoint may lie from the previous one (or from the arm when starting)",
      Range{1e-4, 10});
  c.max_setpoint_rotation = ctx.param<double>(
      "max_setpoint_rotation", 0.5, "rad a setpoint may turn from the previous one (or from the arm)", Range{1e-4, 3.15});
  c.max_setpoint_speed = ctx.param<double>("max_setpoint_speed", 2.0, "m/s, largest linear speed in a setpoint's twist",
                                           Range{1e-3, 100});
  c.max_setpoint_angular_speed = ctx.param<double>(
      "max_setpoint_angular_speed", 6.0, "rad/s, largest angular speed in a setpoint's twist", Range{1e-3, 100});
  c.max_joint_target_step = ctx.param<double>(
      "max_joint_target_step", 0.2, "rad the IK target may move in one servo period (more: an IK branch change, fault)",
      Range{1e-4, 10});
  c.max_following_error = ctx.param<double>(
      "max_following_error", 0.1, "rad between reference and measured joint before a fault", Range{1e-4, 10});
  c.max_force = ctx.param<double>("force_limit", 100.0, "N, measured force norm that faults the arm", Range{0.1, 10000});
  c.max_torque =
      ctx.param<double>("torque_limit", 10.0, "N m, measured torque norm that faults the arm", Range{0.01, 1000});
  if (accel.size() != static_cast<std::size_t>(kDof))
    throw std::invalid_argument("acceleration_limits needs 6 values, one per joint (got " +
                                std::to_string(accel.size()) + ")");
  for (int j = 0; j < kDof; ++j) c.max_acceleration[j] = accel[static_cast<std::size_t>(j)];
  return c;
}

}  // namespace wysiwyf::robot
