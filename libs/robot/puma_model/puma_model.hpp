#pragma once
// The PUMA 560 arm loaded from a URDF (config/robots/puma560.urdf): a serial chain of six
// revolute joints from `base_link` to a tip frame, with every link hanging from it by fixed
// joints (flange, ft_sensor, dev, marker_0..3, knob) as extra frames.
//
// Poses are base_T_<frame> (the frame expressed in base_link). The hot calls (fk, jacobian,
// ik, ik_nearest, dls_step, rnea, mass_matrix, forward_dynamics) allocate nothing, make no
// virtual calls and use only what the constructor precomputed.
#include <array>
#include <string>
#include <vector>

#include "puma_model/ik_result.hpp"
#include "puma_model/types.hpp"

namespace wysiwyf::robot {

class PumaModel {
 public:
  // Loads the URDF at `urdf_path`. Throws std::runtime_error naming the file and what is wrong:
  // unreadable or malformed file, no link `base` or `tip`, `tip` not below `base`, not exactly
  // six revolute joints on the way, a joint axis other than local z, a moving joint off the
  // chain, or joint origins that are not the PUMA's DH geometry (the closed-form IK needs it).
  explicit PumaModel(const std::string& urdf_path, const std::string& tip = "flange",
                     const std::string& base = "base_link");

  // ---- description
  const std::string& urdf_path() const { return urdf_path_; }
  const std::array<std::string, kDof>& joint_names() const { return joint_names_; }
  const JointLimits& limits() const { return limits_; }
  const DhParams& dh() const { return dh_; }
  // Mass properties of moving body k = 1..6 (link k with all links fixed to it: body 6 carries
  // the tool side); body 0 is the base.
  const BodyInertia& body(int k) const { return bodies_[static_cast<std::size_t>(k)]; }

  // ---- frames: every link of the URDF. Throws std::out_of_range for an unknown name.
  FrameId frame(const std::string& name) const;
  FrameId tip() const { return tip_; }
  const std::string& frame_name(FrameId f) const { return frames_[check(f)].name; }
  std::vector<std::string> frame_names() const;
  // The moving body (0..6) a frame is fixed to.
  int frame_body(FrameId f) const { return frames_[check(f)].body; }

  // ---- kinematics
  Eigen::Isometry3d fk(const Vector6d& q) const { return fk(q, tip_); }
  Eigen::Isometry3d fk(const Vector6d& q, FrameId f) const;
  // Geometric Jacobian: [v; w] of the frame's origin, in base coordinates.
  Matrix6d jacobian(const Vector6d& q) const { return jacobian(q, tip_); }
  Matrix6d jacobian(const Vector6d& q, FrameId f) const;

  // All eight closed-form solutions for base_T_frame; `frame` must be fixed to link 6.
  // q_ref picks theta4 at the wrist singularity and the 2 pi representative of each angle.
  IkSolutions ik(const Eigen::Isometry3d& base_T_frame, const Vector6d& q_ref) const {
    return ik(base_T_frame, q_ref, tip_);
  }
  IkSolutions ik(const Eigen::Isometry3d& base_T_frame, const Vector6d& q_ref, FrameId f) const;
  // The solution within limits nearest (Euclidean in joint space) to q_current, or why none.
  IkResult ik_nearest(const Eigen::Isometry3d& base_T_frame, const Vector6d& q_current) const {
    return ik_nearest(base_T_frame, q_current, tip_);
  }
  IkResult ik_nearest(const Eigen::Isometry3d& base_T_frame, const Vector6d& q_current, FrameId f) const;

  // One damped least squares step towards base_T_target: dq = J^T (J J^T + lambda^2 I)^-1 e,
  // e = [position error; rotation vector of R_target R^T], both in base coordinates. Returns
  // dq (apply as q + dq); well behaved through singularities for lambda > 0.
  Vector6d dls_step(const Vector6d& q, const Eigen::Isometry3d& base_T_target, double lambda) const {
    return dls_step(q, base_T_target, lambda, tip_);
  }
  Vector6d dls_step(const Vector6d& q, const Eigen::Isometry3d& base_T_target, double lambda, FrameId f) const;

  // ---- dynamics (gravity: acceleration of gravity in base coordinates)
  // Recursive Newton-Euler: joint torques for q, qd, qdd (plus rotor_inertia .* qdd).
  Vector6d rnea(const Vector6d& q, const Vector6d& qd, const Vector6d& qdd,
                const Eigen::Vector3d& gravity = standard_gravity()) const;
  // Joint-space mass matrix by the composite rigid body algorithm (plus rotor inertia on the
  // diagonal).
  Matrix6d mass_matrix(const Vector6d& q) const;
  Vector6d gravity_torques(const Vector6d& q, const Eigen::Vector3d& gravity = standard_gravity()) const;
  // Coriolis and centrifugal torques C(q, qd) qd.
  Vector6d coriolis(const Vector6d& q, const Vector6d& qd) const;
  // qdd = M(q)^-1 (tau - C(q, qd) qd - g(q)).
  Vector6d forward_dynamics(const Vector6d& q, const Vector6d& qd, const Vector6d& tau,
                            const Eigen::Vector3d& gravity = standard_gravity()) const;

  // Reflected motor inertia G^2 Jm per joint (DriveParams::reflected_inertia()), added to the
  // mass matrix diagonal and to rnea; zero after construction.
  void set_rotor_inertia(const Vector6d& reflected) { rotor_inertia_ = reflected; }
  const Vector6d& rotor_inertia() const { return rotor_inertia_; }

 private:
  struct Frame {
    std::string name;
    int body = 0;                                     // 0 = base, k = moving link k
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // body_T_frame
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
  };
  // Joint j's frame relative to the frame of body j (its parent), before the joint's rotation.
  struct JointOrigin {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
  };
  // Fixed numbers of the closed-form IK, derived from the DH parameters.
  struct IkConstants {
    double d1 = 0, a1 = 0, shoulder_offset = 0;  // shoulder_offset = d2 + d3
    double a2 = 0, l3 = 0, beta = 0;             // forearm length sqrt(a3^2 + d4^2), atan2(d4, a3)
    double cos_beta = 1, sin_beta = 0;
    Eigen::Matrix3d mount_R = Eigen::Matrix3d::Identity();  // base_T_dh0 (joint 1's origin)
    Eigen::Vector3d mount_p = Eigen::Vector3d::Zero();
  };

  std::size_t check(FrameId f) const;
  void fail(const std::string& what) const;  // throws std::runtime_error with the file name
  void load(const std::string& tip, const std::string& base);
  void derive_ik_constants();

  std::string urdf_path_;
  std::array<std::string, kDof> joint_names_;
  JointLimits limits_;
  DhParams dh_;
  std::array<JointOrigin, kDof> joints_;
  std::array<BodyInertia, kDof + 1> bodies_;
  std::vector<Frame> frames_;
  FrameId tip_;
  IkConstants ikc_;
  Vector6d rotor_inertia_ = Vector6d::Zero();
};

}  // namespace wysiwyf::robot
