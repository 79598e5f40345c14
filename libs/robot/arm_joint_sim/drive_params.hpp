#pragma once
// An arm's drive train per joint: gear ratio, rotor inertia and motor-side friction (a drive file
// such as config/robots/puma560_drive.yaml), and what they amount to at the joints. An arm whose
// maker publishes no motor data has ideal drives (DriveParams::ideal): direct drives with no
// rotor inertia and no friction, whose joints are read without encoder quantisation.
#include <string>
#include <vector>

#include "arm_model/arm_types.hpp"

namespace wysiwyf::robot {

struct DriveParams {
  std::vector<std::string> joint_names;  // as the drive file names them, base to tip; empty: ideal drives
  JointVector gear_ratio;                // motor angle = G * joint angle
  JointVector motor_inertia;             // Jm [kg m^2]
  JointVector viscous_friction;          // B [N m s/rad], motor side
  JointVector coulomb_positive;          // Tc+ [N m], motor side, motor velocity > 0
  JointVector coulomb_negative;          // Tc- [N m], motor side, motor velocity < 0

  // Ideal drives of `dof` joints: gear ratio 1, no rotor inertia, no friction, no motor encoder.
  static DriveParams ideal(int dof);
  // Whether these are ideal drives (no drive file: nothing known of the motors).
  bool is_ideal() const { return joint_names.empty(); }
  // The number of joints.
  int dof() const { return static_cast<int>(gear_ratio.size()); }

  // Jm G^2 [kg m^2] at the joint: ArmModel::set_rotor_inertia(drive.reflected_inertia()).
  JointVector reflected_inertia() const;
  // B G^2 [N m s/rad] at the joint.
  JointVector joint_viscous() const;
  // Joint torque spent on friction at joint velocity qd (viscous + Coulomb, no stiction).
  JointVector friction_torque(const JointVector& qd) const;
  // The same with the Coulomb part turned through zero by tanh(qd / smoothing) [rad/s]: the form
  // a simulation integrates (the discontinuous one chatters at a standstill).
  JointVector friction_torque(const JointVector& qd, double smoothing) const;
};

// Reads a drive file (a 'joints' list of 1..kMaxArmDof entries). Throws std::runtime_error naming
// the file and the missing or wrong entry.
DriveParams load_drive_params(const std::string& path);
// Also checks that the file names the arm's joints (`joint_names`, base to tip), in order.
DriveParams load_drive_params(const std::string& path, const std::vector<std::string>& joint_names);

}  // namespace wysiwyf::robot
