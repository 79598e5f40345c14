#include "arm_joint_sim/arm_dynamics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wysiwyf::robot {

ArmDynamics::ArmDynamics(const ArmModel& model, const DriveParams& drive, int encoder_counts, double coulomb_smoothing)
    : model_(model), drive_(drive), coulomb_smoothing_(coulomb_smoothing) {
  const int n = model_.dof();
  if (drive_.dof() != n)
    throw std::invalid_argument("the drive has " + std::to_string(drive_.dof()) + " joints, the arm " +
                                std::to_string(n));
  if (encoder_counts < 0) throw std::invalid_argument("encoder_counts must be >= 0");
  if (!(coulomb_smoothing > 0.0)) throw std::invalid_argument("coulomb_smoothing must be > 0 rad/s");
  quantum_ = JointVector::Zero(n);
  if (!drive_.is_ideal())
    for (int j = 0; j < n; ++j)
      quantum_[j] = encoder_counts > 0 ? 6.283185307179586 / (encoder_counts * std::abs(drive_.gear_ratio[j])) : 0.0;
  q_ = qd_ = JointVector::Zero(n);
}

void ArmDynamics::reset(const JointVector& q) {
  if (q.size() != model_.dof())
    throw std::invalid_argument("ArmDynamics::reset: " + std::to_string(q.size()) + " joint values for an arm of " +
                                std::to_string(model_.dof()));
  q_ = q;
  qd_ = JointVector::Zero(model_.dof());
}

void ArmDynamics::step(double h, const JointVector& motor_torque, const JointVector& external_torque) {
  const JointVector tau = motor_torque + external_torque - friction(qd_);
  const JointVector qdd = model_.forward_dynamics(q_, qd_, tau);
  qd_ += qdd * h;
  q_ += qd_ * h;
}

JointVector ArmDynamics::measured_q() const {
  JointVector q(q_.size());
  for (int j = 0; j < q_.size(); ++j) q[j] = quantum_[j] > 0.0 ? std::round(q_[j] / quantum_[j]) * quantum_[j] : q_[j];
  return q;
}

}  // namespace wysiwyf::robot
