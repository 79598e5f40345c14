#pragma once
// Fixed-size types shared by the PUMA model: joint vectors, limits, link inertia, frame ids.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wysiwyf::robot {

constexpr int kDof = 6;
using Vector6d = Eigen::Matrix<double, kDof, 1>;
using Matrix6d = Eigen::Matrix<double, kDof, kDof>;

// Gravity in the base frame used when a call does not give one [m/s^2].
inline Eigen::Vector3d standard_gravity() { return {0.0, 0.0, -9.81}; }

// Per joint, from the URDF <limit>: position [rad], velocity [rad/s], effort [N m].
struct JointLimits {
  Vector6d lower = Vector6d::Zero();
  Vector6d upper = Vector6d::Zero();
  Vector6d velocity = Vector6d::Zero();
  Vector6d effort = Vector6d::Zero();

  bool within(const Vector6d& q, double tolerance = 0.0) const {
    return ((q.array() >= lower.array() - tolerance) && (q.array() <= upper.array() + tolerance)).all();
  }
};

// Mass properties of one rigid body (a moving link with everything fixed to it), in the body's
// own frame: mass [kg], centre of mass [m], inertia about the centre of mass [kg m^2].
struct BodyInertia {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

// A named frame of the model (a URDF link), resolved once by PumaModel::frame(name).
struct FrameId {
  int index = -1;
  friend bool operator==(FrameId a, FrameId b) { return a.index == b.index; }
  friend bool operator!=(FrameId a, FrameId b) { return a.index != b.index; }
};

// Standard DH parameters of the arm, read from the URDF joint origins (see puma560.urdf):
// A_i = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i), i = 1..5 (link 6's part lies in the tool frames).
struct DhParams {
  double d[5] = {};
  double a[5] = {};
  double alpha[5] = {};
};

}  // namespace wysiwyf::robot
