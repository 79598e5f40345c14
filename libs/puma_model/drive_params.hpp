#pragma once
// The PUMA's drive train (config/robots/puma560_drive.yaml): gear ratios, rotor inertia and
// motor-side friction, and what they amount to at the joints.
#include <array>
#include <string>

#include "puma_model/types.hpp"

namespace wysiwyf::robot {

class PumaModel;

struct DriveParams {
  std::array<std::string, kDof> joint_names;
  Vector6d gear_ratio = Vector6d::Ones();        // motor angle = G * joint angle
  Vector6d motor_inertia = Vector6d::Zero();     // Jm [kg m^2]
  Vector6d viscous_friction = Vector6d::Zero();  // B [N m s/rad], motor side
  Vector6d coulomb_positive = Vector6d::Zero();  // Tc+ [N m], motor side, motor velocity > 0
  Vector6d coulomb_negative = Vector6d::Zero();  // Tc- [N m], motor side, motor velocity < 0

  // Jm G^2 [kg m^2] at the joint: PumaModel::set_rotor_inertia(drive.reflected_inertia()).
  Vector6d reflected_inertia() const;
  // B G^2 [N m s/rad] at the joint.
  Vector6d joint_viscous() const;
  // Joint torque spent on friction at joint velocity qd (viscous + Coulomb, no stiction).
  Vector6d friction_torque(const Vector6d& qd) const;
  // The same with the Coulomb part turned through zero by tanh(qd / smoothing) [rad/s]: the form
  // a simulation integrates (the discontinuous one chatters at a standstill).
  Vector6d friction_torque(const Vector6d& qd, double smoothing) const;
};

// Throws std::runtime_error naming the file and the missing or wrong entry.
DriveParams load_drive_params(const std::string& path);
// Also checks that the file names the model's joints, in order.
DriveParams load_drive_params(const std::string& path, const PumaModel& model);

}  // namespace wysiwyf::robot
