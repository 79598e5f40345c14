#pragma once
// An arm's 1 kHz joint servo, as in the Unimation controller: PD on the joint reference plus
// gravity compensation, and (not in the Unimation servo; on by default) inverse-dynamics and
// friction feedforward. Torques are saturated at the URDF effort limits.
//
// Derived gains depend on the drives. Geared drives (a drive file) have one PD per joint, scaled
// by that joint's inertia M_jj(q_gains): the reflected rotor inertia dominates and decouples the
// joints, as in the PUMA's cabinet. Ideal drives have no rotor inertia, and the links' inertia
// couples the joints (an FR3's joints 1 and 3 nearly share an axis while joint 2 is near 0: one
// PD per joint would be unstable in their opposed motion), so the PD acts through the mass matrix
// at the measured joints, tau = M(q) (w^2 e + 2 zeta w e'): every joint-space mode then has the
// bandwidth w, as a model-based joint controller gives it. Explicit gains are always per joint.
#include <vector>

#include "arm_joint_sim/drive_params.hpp"
#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot {

struct JointServoConfig {
  double bandwidth_hz = 10.0;         // derived gains: kp = M_jj w^2, kd = 2 zeta M_jj w, w = 2 pi this
  double damping = 1.0;               // zeta of the derived gains
  std::vector<double> kp, kd;         // explicit gains per joint (empty: derived from M(q_gains))
  double accel_feedforward = 1.0;     // share of M(q) qdd_ref + C(q, qd) qd added
  double friction_feedforward = 1.0;  // share of the drive friction added while the reference moves
  double coulomb_smoothing = 0.01;    // rad/s over which the Coulomb model turns (tanh)

  // Throws std::invalid_argument naming the value that does not fit an arm of `dof` joints.
  void validate(int dof) const;
};

class JointServo {
 public:
  // The model and drive (of the model's joint count) must outlive the servo; q_gains: the pose
  // whose mass matrix sets the derived gains. Throws std::invalid_argument when they do not fit.
  JointServo(const ArmModel& model, const DriveParams& drive, const JointServoConfig& config,
             const JointVector& q_gains);

  // Motor torques at the joints for the measured joints, towards the reference: position and
  // velocity now, and the acceleration that takes it to the next period (feedforward).
  JointVector torque(const JointVector& q_measured, const JointVector& qd_measured, const JointVector& ref_q,
                     const JointVector& ref_qd, const JointVector& ref_qdd) const;

  // Whether the PD acts through the mass matrix (derived gains on ideal drives).
  bool inertia_weighted() const { return inertia_weighted_; }
  // Per-joint gains [N m/rad, N m s/rad]; when inertia_weighted(), w^2 and 2 zeta w [1/s^2, 1/s]
  // on every joint, multiplied by M(q).
  const JointVector& kp() const { return kp_; }
  const JointVector& kd() const { return kd_; }

 private:
  const ArmModel& model_;
  const DriveParams& drive_;
  JointServoConfig config_;
  bool inertia_weighted_ = false;
  JointVector kp_, kd_;
};

}  // namespace wysiwyf::robot
