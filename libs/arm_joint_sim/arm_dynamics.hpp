#pragma once
// The PUMA's joints as a simulated plant: forward dynamics with reflected rotor inertia, viscous
// and (tanh-smoothed) Coulomb drive friction, semi-implicit Euler steps, and encoders that
// quantise what the servo measures.
#include "puma_model/drive_params.hpp"
#include "puma_model/puma_model.hpp"

namespace wysiwyf::robot {

class ArmDynamics {
 public:
  // The model (with the rotor inertia set) and the drive must outlive this. encoder_counts: per
  // motor revolution after quadrature (0: no quantisation).
  ArmDynamics(const PumaModel& model, const DriveParams& drive, int encoder_counts, double coulomb_smoothing);

  // At rest at q.
  void reset(const Vector6d& q);
  // One semi-implicit Euler step of h seconds under the motor torques and an external torque at
  // the joints (contact reactions).
  void step(double h, const Vector6d& motor_torque, const Vector6d& external_torque);

  const Vector6d& q() const { return q_; }
  const Vector6d& qd() const { return qd_; }
  // The encoder reading of q: a multiple of 2 pi / (counts |gear|) per joint.
  Vector6d measured_q() const;
  const Vector6d& quantum() const { return quantum_; }
  Vector6d friction(const Vector6d& qd) const { return drive_.friction_torque(qd, coulomb_smoothing_); }

 private:
  const PumaModel& model_;
  const DriveParams& drive_;
  double coulomb_smoothing_;
  Vector6d quantum_ = Vector6d::Zero();
  Vector6d q_ = Vector6d::Zero(), qd_ = Vector6d::Zero();
};

}  // namespace wysiwyf::robot
