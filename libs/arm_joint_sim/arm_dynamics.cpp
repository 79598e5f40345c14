#include "arm_joint_sim/arm_dynamics.hpp"

#include <cmath>
#include <stdexcept>

namespace wysiwyf::robot {

ArmDynamics::ArmDynamics(const PumaModel& model, const DriveParams& drive, int encoder_counts, double coulomb_smoothing)
    : model_(model), drive_(drive), coulomb_smoothing_(coulomb_smoothing) {
  if (encoder_counts < 0) throw std::invalid_argument("encoder_counts must be >= 0");
  if (!(coulomb_smoothing > 0.0)) throw std::invalid_argument("coulomb_smoothing must be > 0 rad/s");
  for (int j = 0; j < kDof; ++j)
    quantum_[j] = encoder_counts > 0 ? 6.283185307179586 / (encoder_counts * std::abs(drive_.gear_ratio[j])) : 0.0;
}

void ArmDynamics::reset(const Vector6d& q) {
  q_ = q;
  qd_ = Vector6d::Zero();
}

void ArmDynamics::step(double h, const Vector6d& motor_torque, const Vector6d& external_torque) {
  const Vector6d qdd = model_.forward_dynamics(q_, qd_, motor_torque + external_torque - friction(qd_));
  qd_ += qdd * h;
  q_ += qd_ * h;
}

Vector6d ArmDynamics::measured_q() const {
  Vector6d q;
  for (int j = 0; j < kDof; ++j) q[j] = quantum_[j] > 0.0 ? std::round(q_[j] / quantum_[j]) * quantum_[j] : q_[j];
  return q;
}

}  // namespace wysiwyf::robot
