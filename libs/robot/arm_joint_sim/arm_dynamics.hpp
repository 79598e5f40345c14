#pragma once
// An arm's joints as a simulated plant: forward dynamics with reflected rotor inertia, viscous
// and (tanh-smoothed) Coulomb drive friction, semi-implicit Euler steps, and encoders that
// quantise what the servo measures (on the motor side, so not for ideal drives).
#include "arm_joint_sim/drive_params.hpp"
#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot {

class ArmDynamics {
 public:
  // The model (with the rotor inertia set) and the drive (of the model's joint count) must
  // outlive this. encoder_counts: per motor revolution after quadrature (0: no quantisation;
  // ideal drives have no motor, so no quantisation either). Throws std::invalid_argument for a
  // drive of another joint count, negative counts or a smoothing <= 0.
  ArmDynamics(const ArmModel& model, const DriveParams& drive, int encoder_counts, double coulomb_smoothing);

  // At rest at q (the model's joint count).
  void reset(const JointVector& q);
  // One semi-implicit Euler step of h seconds under the motor torques and an external torque at
  // the joints (contact reactions).
  void step(double h, const JointVector& motor_torque, const JointVector& external_torque);

  const JointVector& q() const { return q_; }
  const JointVector& qd() const { return qd_; }
  // The encoder reading of q: a multiple of 2 pi / (counts |gear|) per joint.
  JointVector measured_q() const;
  const JointVector& quantum() const { return quantum_; }
  JointVector friction(const JointVector& qd) const { return drive_.friction_torque(qd, coulomb_smoothing_); }

 private:
  const ArmModel& model_;
  const DriveParams& drive_;
  double coulomb_smoothing_;
  JointVector quantum_, q_, qd_;
};

}  // namespace wysiwyf::robot
