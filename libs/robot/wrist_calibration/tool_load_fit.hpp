#pragma once
// The wrist sensor's bias and the tool's load from static poses. At rest the sensor reads, in its
// own frame, F = F0 + m g and T = T0 + c x (m g), g the gravity in the sensor frame (the arm's
// forward kinematics), m the tool's mass, c its centre of mass, F0 and T0 the bias. Both are
// linear: [I g] [F0; m] = F and [I -[g]x] [T0; m c] = T, solved by least squares over every pose.
// A set of poses whose gravity directions do not span enough (the design's condition number, on
// unit gravity directions so that it does not depend on units) is refused, as is a fit that leaves
// a pose's residual above its threshold (the tool moved, the arm was not at rest, a reading was
// taken under load).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace wysiwyf::robot {

// One static pose: gravity in the sensor frame and what the sensor read there (averaged at rest).
struct WristReading {
  std::string label;                                         // how reports name the pose ("pose 3")
  Eigen::Vector3d gravity_sensor = Eigen::Vector3d::Zero();  // m/s^2, sensor frame
  Eigen::Vector3d force = Eigen::Vector3d::Zero();           // N, sensor frame
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();          // N m, sensor frame, about its origin
};

struct ToolLoadLimits {
  int min_poses = 6;                  // fewer is refused
  double max_condition = 10.0;        // of the torque design on unit gravity directions (1.2: directions all round)
  double max_force_residual = 0.5;    // N, per pose
  double max_torque_residual = 0.05;  // N m, per pose
};

struct PoseResidual {
  std::string label;
  double force = 0;   // N, |measured - fitted|
  double torque = 0;  // N m
};

struct ToolLoadFit {
  bool accepted = false;
  std::string refusal;                                    // why not accepted, what to do; empty when accepted
  Eigen::Vector3d force_bias = Eigen::Vector3d::Zero();   // N, sensor frame
  Eigen::Vector3d torque_bias = Eigen::Vector3d::Zero();  // N m
  double tool_mass = 0;                                   // kg
  Eigen::Vector3d tool_com = Eigen::Vector3d::Zero();     // m, sensor frame
  double condition = 0;                                   // the larger of the force and torque designs'
  std::vector<PoseResidual> residuals;                    // one per reading, in order
  double force_rms = 0, torque_rms = 0;                   // over every pose
};

// Fits bias, mass and centre of mass. Never throws: an unusable set comes back refused with the
// reason (too few poses, non-finite values, a condition number over the limit, a residual over it).
ToolLoadFit fit_tool_load(const std::vector<WristReading>& readings, const ToolLoadLimits& limits = {});

// The report a person reads: the estimate, the condition number, the residual of every pose.
std::string describe(const ToolLoadFit& fit, const ToolLoadLimits& limits);

}  // namespace wysiwyf::robot
