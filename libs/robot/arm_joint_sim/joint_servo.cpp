#include "arm_joint_sim/joint_servo.hpp"

#include <stdexcept>
#include <string>

namespace wysiwyf::robot {

void JointServoConfig::validate(int dof) const {
  auto one_per_joint_or_none = [dof](const std::vector<double>& v, const char* name) {
    if (!v.empty() && v.size() != static_cast<std::size_t>(dof))
      throw std::invalid_argument(std::string(name) + " needs " + std::to_string(dof) +
                                  " values, one per joint, or none (got " + std::to_string(v.size()) + ")");
    for (double x : v)
      if (!(x >= 0.0)) throw std::invalid_argument(std::string(name) + " must be >= 0 (got " + std::to_string(x) + ")");
  };
  one_per_joint_or_none(kp, "servo_kp");
  one_per_joint_or_none(kd, "servo_kd");
  if (!(bandwidth_hz > 0.0)) throw std::invalid_argument("servo bandwidth must be > 0 Hz");
  if (!(damping > 0.0)) throw std::invalid_argument("servo damping must be > 0");
  if (!(coulomb_smoothing > 0.0)) throw std::invalid_argument("coulomb_smoothing must be > 0 rad/s");
}

JointServo::JointServo(const ArmModel& model, const DriveParams& drive, const JointServoConfig& config,
                       const JointVector& q_gains)
    : model_(model), drive_(drive), config_(config) {
  const int n = model_.dof();
  config_.validate(n);
  if (drive_.dof() != n)
    throw std::invalid_argument("the drive has " + std::to_string(drive_.dof()) + " joints, the arm " +
                                std::to_string(n));
  const double w = 6.283185307179586 * config_.bandwidth_hz;
  inertia_weighted_ = drive_.is_ideal() && config_.kp.empty() && config_.kd.empty();
  if (inertia_weighted_) {
    kp_ = JointVector::Constant(n, w * w);
    kd_ = JointVector::Constant(n, 2.0 * config_.damping * w);
    return;
  }
  const JointVector m_diag = model_.mass_matrix(q_gains).diagonal();
  kp_.resize(n);
  kd_.resize(n);
  for (int j = 0; j < n; ++j) {
    const auto k = static_cast<std::size_t>(j);
    kp_[j] = config_.kp.empty() ? m_diag[j] * w * w : config_.kp[k];
    kd_[j] = config_.kd.empty() ? 2.0 * config_.damping * m_diag[j] * w : config_.kd[k];
  }
}

JointVector JointServo::torque(const JointVector& q_measured, const JointVector& qd_measured, const JointVector& ref_q,
                               const JointVector& ref_qd, const JointVector& ref_qdd) const {
  const JointVector gravity = model_.gravity_torques(q_measured);
  const JointVector pd = kp_.cwiseProduct(ref_q - q_measured) + kd_.cwiseProduct(ref_qd - qd_measured);
  JointVector tau =
      inertia_weighted_ ? JointVector(model_.mass_matrix(q_measured) * pd + gravity) : JointVector(pd + gravity);
  if (config_.accel_feedforward > 0.0)
    tau += config_.accel_feedforward * (model_.rnea(q_measured, qd_measured, ref_qdd) - gravity);
  // Friction is compensated while the reference moves; at a standstill it holds the arm (and
  // damps the hunting that encoder quantisation would give a frictionless joint).
  if (config_.friction_feedforward > 0.0) {
    const JointVector f = drive_.friction_torque(qd_measured, config_.coulomb_smoothing);
    for (int j = 0; j < tau.size(); ++j)
      if (ref_qd[j] != 0.0 || ref_qdd[j] != 0.0) tau[j] += config_.friction_feedforward * f[j];
  }
  const JointVector& effort = model_.limits().effort;
  return tau.cwiseMax(-effort).cwiseMin(effort);
}

}  // namespace wysiwyf::robot
