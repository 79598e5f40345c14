// Rigid-body dynamics of the arm in the URDF link frames: recursive Newton-Euler (inverse
// dynamics), composite rigid body (mass matrix) and forward dynamics. Body k = link k with every
// link fixed to it (the constructor merged their inertias); joint k-1 turns it about its local z.
#include <Eigen/Cholesky>

#include "puma_model/puma_model.hpp"
#include "puma_model/rigid.hpp"

namespace wysiwyf::robot {

Vector6d PumaModel::rnea(const Vector6d& q, const Vector6d& qd, const Vector6d& qdd,
                         const Eigen::Vector3d& gravity) const {
  std::array<Eigen::Matrix3d, kDof> parent_R;  // parent_R_body
  std::array<Eigen::Vector3d, kDof> force, moment;
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  // of the parent, in the parent's frame
  Eigen::Vector3d wd = Eigen::Vector3d::Zero();
  Eigen::Vector3d a = -gravity;  // origin acceleration, gravity folded in

  for (int j = 0; j < kDof; ++j) {
    const JointOrigin& o = joints_[static_cast<std::size_t>(j)];
    Eigen::Matrix3d R = o.R;
    detail::post_rotate_z(R, std::cos(q[j]), std::sin(q[j]));
    parent_R[static_cast<std::size_t>(j)] = R;
    const Eigen::Vector3d a_origin = R.transpose() * (a + wd.cross(o.p) + w.cross(w.cross(o.p)));
    const Eigen::Vector3d w_in = R.transpose() * w;
    Eigen::Vector3d wd_new = R.transpose() * wd;
    wd_new.x() += w_in.y() * qd[j];  // w_in x (qd z)
    wd_new.y() -= w_in.x() * qd[j];
    wd_new.z() += qdd[j];
    w = w_in;
    w.z() += qd[j];
    wd = wd_new;
    a = a_origin;

    const BodyInertia& b = bodies_[static_cast<std::size_t>(j + 1)];
    const Eigen::Vector3d a_com = a + wd.cross(b.com) + w.cross(w.cross(b.com));
    force[static_cast<std::size_t>(j)] = b.mass * a_com;
    moment[static_cast<std::size_t>(j)] = b.inertia * wd + w.cross(b.inertia * w);
  }

  Vector6d tau;
  Eigen::Vector3d f = Eigen::Vector3d::Zero();  // exerted on body j+1 by body j, body j+1's frame
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int j = kDof - 1; j >= 0; --j) {
    const std::size_t k = static_cast<std::size_t>(j);
    const BodyInertia& b = bodies_[k + 1];
    Eigen::Vector3d n_new = moment[k] + b.com.cross(force[k]);
    Eigen::Vector3d f_new = force[k];
    if (j + 1 < kDof) {
      const Eigen::Vector3d f_child = parent_R[k + 1] * f;
      n_new += parent_R[k + 1] * n + joints_[k + 1].p.cross(f_child);
      f_new += f_child;
    }
    f = f_new;
    n = n_new;
    tau[j] = n.z() + rotor_inertia_[j] * qdd[j];
  }
  return tau;
}

Matrix6d PumaModel::mass_matrix(const Vector6d& q) const {
  // Every body's spatial inertia about the base origin (mass, first moment, rotational
  // inertia), and every joint's motion axis S_j = [z_j; p_j x z_j], in base coordinates.
  std::array<double, kDof> mass;
  std::array<Eigen::Vector3d, kDof> first_moment, axis, axis_moment;
  std::array<Eigen::Matrix3d, kDof> inertia;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int j = 0; j < kDof; ++j) {
    const std::size_t k = static_cast<std::size_t>(j);
    const JointOrigin& o = joints_[k];
    p += R * o.p;
    R = R * o.R;
    axis[k] = R.col(2);
    axis_moment[k] = p.cross(axis[k]);
    detail::post_rotate_z(R, std::cos(q[j]), std::sin(q[j]));
    const BodyInertia& b = bodies_[k + 1];
    const Eigen::Vector3d c = p + R * b.com;
    mass[k] = b.mass;
    first_moment[k] = b.mass * c;
    inertia[k] =
        R * b.inertia * R.transpose() + b.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  }

  Matrix6d M;
  double m_c = 0.0;
  Eigen::Vector3d h_c = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I_c = Eigen::Matrix3d::Zero();
  for (int j = kDof - 1; j >= 0; --j) {
    const std::size_t k = static_cast<std::size_t>(j);
    m_c += mass[k];  // composite of bodies j+1 .. 6
    h_c += first_moment[k];
    I_c += inertia[k];
    // Force (about the base origin) to accelerate the composite at unit speed about S_j.
    const Eigen::Vector3d moment = I_c * axis[k] + h_c.cross(axis_moment[k]);
    const Eigen::Vector3d force = m_c * axis_moment[k] + axis[k].cross(h_c);
    for (int i = 0; i <= j; ++i) {
      const std::size_t l = static_cast<std::size_t>(i);
      M(i, j) = M(j, i) = axis[l].dot(moment) + axis_moment[l].dot(force);
    }
    M(j, j) += rotor_inertia_[j];
  }
  return M;
}

Vector6d PumaModel::gravity_torques(const Vector6d& q, const Eigen::Vector3d& gravity) const {
  return rnea(q, Vector6d::Zero(), Vector6d::Zero(), gravity);
}

Vector6d PumaModel::coriolis(const Vector6d& q, const Vector6d& qd) const {
  return rnea(q, qd, Vector6d::Zero(), Eigen::Vector3d::Zero());
}

Vector6d PumaModel::forward_dynamics(const Vector6d& q, const Vector6d& qd, const Vector6d& tau,
                                     const Eigen::Vector3d& gravity) const {
  const Vector6d bias = rnea(q, qd, Vector6d::Zero(), gravity);
  return mass_matrix(q).ldlt().solve(tau - bias);
}

}  // namespace wysiwyf::robot
