#include "arm_interface/arm_params.hpp"

#include <stdexcept>
#include <string>

#include "arm_interface/arm_ports.hpp"
#include "wysiwyf/config_files.hpp"

namespace wysiwyf::robot {

ArmParams declare_arm_params(Context& ctx) {
  ArmParams p;
  p.urdf_path = ctx.param<std::string>(
      "urdf", "robots/puma560.urdf", "robot URDF; relative paths are looked up in the working directory, then config/");
  p.tip_frame = ctx.param<std::string>("tip_frame", "dev",
                                       "the frame the Cartesian setpoints place (fixed to the arm's last link)");
  p.tracker_hz =
      ctx.param<double>("tracker_bandwidth_hz", 10.0,
                        "natural frequency of the critically damped Cartesian setpoint tracker, Hz", Range{0.1, 200});
  p.setpoint_source = ctx.param<std::string>(
      "setpoint_source", "",
      "accept setpoints only from sources that begin so (e.g. supervisor: the display's one voice); empty: any");
  SafetyConfig& c = p.gate;
  p.acceleration_limits = ctx.param<std::vector<double>>(
      "acceleration_limits", {8, 8, 10, 30, 30, 30},
      "hard joint acceleration limits, rad/s^2, one per joint of the URDF (which has none; the default is the PUMA "
      "560's); the reference uses acceleration_fraction of them",
      Range{0.01, 1000}, Length{1, static_cast<std::size_t>(kMaxArmDof), 1, false});
  c.velocity_fraction = ctx.param<double>(
      "velocity_fraction", 0.9, "share of the URDF velocity limits the reference may use (the rest is servo margin)",
      Range{0.05, 1});
  c.acceleration_fraction = ctx.param<double>("acceleration_fraction", 0.8,
                                              "share of acceleration_limits the reference may use", Range{0.05, 1});
  c.position_margin = ctx.param<double>("position_margin", 0.02,
                                        "rad kept between the reference and every joint position limit", Range{0, 0.5});
  c.approach_rate =
      ctx.param<double>("approach_rate", 50.0,
                        "1/s, first-order rate at which the reference closes the last bit of a move", Range{1, 2000});
  c.setpoint_timeout = ctx.param<double>("setpoint_timeout", 0.06,
                                         "s without a setpoint before braking to a hold, at most (3 periods of a 20 ms "
                                         "stream; the stream's own period, learned, sets it below that)",
                                         Range{0.002, 10});
  c.setpoint_periods = ctx.param<double>(
      "setpoint_periods", 3.0, "the stream is lost after this many of its own (learned) periods without a setpoint",
      Range{1, 100});
  c.max_setpoint_age =
      ctx.param<double>("max_setpoint_age", 0.05,
                        "s: a setpoint stamped longer ago (by the arm's clock) is stale and refused", Range{0.001, 10});
  c.max_setpoint_lead = ctx.param<double>(
      "max_setpoint_lead", 0.005,
      "s: a setpoint stamped further ahead of the arm's clock is refused (allow for the hosts' clock sync)",
      Range{0, 1});
  c.max_setpoint_step =
      ctx.param<double>("max_setpoint_step", 0.1,
                        "m a setpoint may lie from the previous one (or from the arm when starting)", Range{1e-4, 10});
  c.max_setpoint_rotation =
      ctx.param<double>("max_setpoint_rotation", 0.5, "rad a setpoint may turn from the previous one (or from the arm)",
                        Range{1e-4, 3.15});
  c.max_setpoint_speed =
      ctx.param<double>("max_setpoint_speed", 2.0, "m/s, largest linear speed in a setpoint's twist", Range{1e-3, 100});
  c.max_setpoint_angular_speed = ctx.param<double>(
      "max_setpoint_angular_speed", 6.0, "rad/s, largest angular speed in a setpoint's twist", Range{1e-3, 100});
  c.max_joint_target_step = ctx.param<double>(
      "max_joint_target_step", 0.2, "rad the IK target may move in one servo period (more: an IK branch change, fault)",
      Range{1e-4, 10});
  c.max_following_error = ctx.param<double>("max_following_error", 0.1,
                                            "rad between reference and measured joint before a fault", Range{1e-4, 10});
  c.max_force =
      ctx.param<double>("force_limit", 100.0, "N, measured force norm that faults the arm", Range{0.1, 10000});
  c.max_torque =
      ctx.param<double>("torque_limit", 10.0, "N m, measured torque norm that faults the arm", Range{0.01, 1000});
  c.dt = ctx.period_ns() > 0 ? static_cast<double>(ctx.period_ns()) * 1e-9 : 1e-3;
  if (c.approach_rate * c.dt > 2.0)  // the braking set must stay invariant over one period
    ctx.reject("approach_rate", "must be at most 2 / period = " + std::to_string(2.0 / c.dt) + " 1/s at this rate");
  return p;
}

std::string ArmParams::source_problem(const msg::CartesianSetpoint& m) const {
  const std::string_view source = m.source().c_str();
  if (setpoint_source.empty() || source.substr(0, setpoint_source.size()) == setpoint_source) return {};
  return "source '" + std::string(source) + "', expected one beginning '" + setpoint_source + "'";
}

std::unique_ptr<ArmModel> load_arm_model(Context& ctx, ArmParams& params) {
  std::unique_ptr<ArmModel> model;
  try {
    model = std::make_unique<ArmModel>(find_config_file(params.urdf_path), params.tip_frame);
  } catch (const std::exception& e) {
    ctx.reject("urdf", e.what());
    return nullptr;
  }
  const int n = model->dof();
  if (model->frame_body(model->tip()) != n) {
    ctx.reject("tip_frame", "'" + params.tip_frame + "' is not fixed to the last link (after joint " +
                                std::to_string(n) + ") of " + params.urdf_path);
    return nullptr;
  }
  if (!joint_state_carries(n)) {
    ctx.reject("urdf", params.urdf_path + " has " + std::to_string(n) + " joints; the JointState message carries " +
                           joint_state_capacity());
    return nullptr;
  }
  if (params.acceleration_limits.size() != static_cast<std::size_t>(n)) {
    ctx.reject("acceleration_limits", "needs one value per joint of " + params.urdf_path + ": " + std::to_string(n) +
                                          " values, got " + std::to_string(params.acceleration_limits.size()));
    return nullptr;
  }
  params.gate.max_acceleration = Eigen::Map<const Eigen::VectorXd>(params.acceleration_limits.data(), n);
  params.gate.limits = model->limits();
  try {
    params.gate.validate();
  } catch (const std::invalid_argument& e) {  // (each value is in range: what is left is the margin against the limits)
    ctx.reject("position_margin", e.what());
    return nullptr;
  }
  return model;
}

}  // namespace wysiwyf::robot
