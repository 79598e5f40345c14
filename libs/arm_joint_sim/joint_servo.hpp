#pragma once
// The PUMA's 1 kHz joint servo, as in the Unimation controller: PD on the joint reference plus
// gravity compensation, and (not in the Unimation servo; on by default) inverse-dynamics and
// friction feedforward. Torques are saturated at the URDF effort limits.
#include <vector>

#include "puma_model/drive_params.hpp"
#include "puma_model/puma_model.hpp"

namespace wysiwyf::robot {

struct JointServoConfig {
  double bandwidth_hz = 10.0;         // derived gains: kp = M_jj w^2, kd = 2 zeta M_jj w, w = 2 pi this
  double damping = 1.0;               // zeta of the derived gains
  std::vector<double> kp, kd;         // explicit gains per joint (empty: derived from M(q_gains))
  double accel_feedforward = 1.0;     // share of M(q) qdd_ref + C(q, qd) qd added
  double friction_feedforward = 1.0;  // share of the drive friction added while the reference moves
  double coulomb_smoothing = 0.01;    // rad/s over which the Coulomb model turns (tanh)

  // Throws std::invalid_argument naming the value that does not fit.
  void validate() const;
};

class JointServo {
 public:
  // The model and drive must outlive the servo; q_gains: the pose whose mass matrix sets the
  // derived gains.
  JointServo(const PumaModel& model, const DriveParams& drive, const JointServoConfig& config, const Vector6d& q_gains);

  // Motor torques at the joints for the measured joints, towards the reference: position and
  // velocity now, and the acceleration that takes it to the next period (feedforward).
  Vector6d torque(const Vector6d& q_measured, const Vector6d& qd_measured, const Vector6d& ref_q,
                  const Vector6d& ref_qd, const Vector6d& ref_qdd) const;

  const Vector6d& kp() const { return kp_; }
  const Vector6d& kd() const { return kd_; }

 private:
  const PumaModel& model_;
  const DriveParams& drive_;
  JointServoConfig config_;
  Vector6d kp_, kd_;
};

}  // namespace wysiwyf::robot
