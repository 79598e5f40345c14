// Standard DH parameters from the joint axes at q = 0 (the construction in dh_geometry.hpp), the
// DH forward product, and the UR-type geometry test.
#include "arm_model/dh_geometry.hpp"

#include <cmath>
#include <sstream>

namespace wysiwyf::robot::detail {
namespace {

constexpr double kParallel = 1e-12;  // |z_a x z_b| below this: parallel axes
constexpr double kTol = 1e-9;        // on the UR geometry test [rad, m]
constexpr double kHalfPi = 1.5707963267948966;

Eigen::Isometry3d frame_of(const Eigen::Vector3d& origin, const Eigen::Vector3d& x, const Eigen::Vector3d& z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = z.cross(x);
  T.linear().col(2) = z;
  T.translation() = origin;
  return T;
}

}  // namespace

Eigen::Isometry3d dh_transform(double theta, double d, double a, double alpha) {
  const double ct = std::cos(theta), st = std::sin(theta), ca = std::cos(alpha), sa = std::sin(alpha);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0.0, sa, ca;
  T.translation() = Eigen::Vector3d(a * ct, a * st, d);
  return T;
}

DhChain dh_from_axes(const AxisLine* axes, int n, const Eigen::Isometry3d& base_T_body_at_zero) {
  DhChain dh;
  dh.n = n;
  std::array<Eigen::Vector3d, kMaxArmDof + 1> origin, x, z;
  z[0] = axes[0].direction;
  x[0] = z[0].unitOrthogonal();  // replaced by x1 when there is a joint 2
  // Frame 0's origin: the foot of the base origin on joint 1's axis.
  origin[0] = axes[0].point - axes[0].direction * axes[0].point.dot(axes[0].direction);
  for (int i = 1; i < n; ++i) {
    const Eigen::Vector3d& u0 = axes[i - 1].direction;
    const Eigen::Vector3d& u1 = axes[i].direction;
    const Eigen::Vector3d& p1 = axes[i].point;
    z[i] = u1;
    const Eigen::Vector3d c = u0.cross(u1);
    Eigen::Vector3d xi;
    if (c.norm() > kParallel) {
      // Common normal of two skew (or intersecting) lines: its foot on line i is frame i's origin.
      xi = c.normalized();
      const Eigen::Vector3d w = p1 - axes[i - 1].point;
      const double b = u0.dot(u1), denom = 1.0 - b * b;
      const double t1 = (b * w.dot(u0) - w.dot(u1)) / denom;  // along u1 from p1
      origin[i] = p1 + t1 * u1;
    } else {
      // Parallel axes: the normal through the previous origin (d_i = 0).
      const Eigen::Vector3d w = p1 - origin[i - 1];
      const Eigen::Vector3d w_perp = w - w.dot(u1) * u1;
      origin[i] = origin[i - 1] + w_perp;
      xi = w_perp.norm() > kParallel ? Eigen::Vector3d(w_perp.normalized()) : x[i - 1];
    }
    if (i >= 2 && xi.dot(x[i - 1]) < 0.0) xi = -xi;
    x[i] = xi;
    if (i == 1) x[0] = xi;  // x0 = x1: joint 1 has no offset at q = 0
  }
  // Frame n: frame n-1 turned by joint n.
  origin[n] = origin[n - 1];
  x[n] = x[n - 1];
  z[n] = z[n - 1];

  for (int i = 1; i <= n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i - 1);
    const Eigen::Vector3d step = origin[i] - origin[i - 1];
    dh.d[k] = step.dot(z[i - 1]);
    dh.a[k] = step.dot(x[i]);
    dh.alpha[k] = std::atan2(z[i - 1].cross(z[i]).dot(x[i]), z[i - 1].dot(z[i]));
    dh.offset[k] = std::atan2(x[i - 1].cross(x[i]).dot(z[i - 1]), x[i - 1].dot(x[i]));
  }
  dh.base_T_dh0 = frame_of(origin[0], x[0], z[0]);
  dh.dhn_T_body = frame_of(origin[n], x[n], z[n]).inverse() * base_T_body_at_zero;
  return dh;
}

Eigen::Isometry3d dh_forward(const DhChain& dh, const JointRef& q) {
  Eigen::Isometry3d T = dh.base_T_dh0;
  for (int i = 0; i < dh.n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    T = T * dh_transform(q[i] + dh.offset[k], dh.d[k], dh.a[k], dh.alpha[k]);
  }
  return T * dh.dhn_T_body;
}

std::string ur_geometry_mismatch(const DhChain& dh) {
  if (dh.n != 6) return "not 6 joints";
  std::ostringstream bad;
  const double alpha[6] = {kHalfPi, 0.0, 0.0, kHalfPi, -kHalfPi, 0.0};
  for (int i = 0; i < 6; ++i)
    if (std::abs(dh.alpha[static_cast<std::size_t>(i)] - alpha[i]) > kTol)
      bad << " alpha" << i + 1 << " = " << dh.alpha[static_cast<std::size_t>(i)] << " (need " << alpha[i] << ")";
  if (std::abs(dh.a[3]) > kTol) bad << " a4 = " << dh.a[3] << " (need 0)";
  if (std::abs(dh.a[4]) > kTol) bad << " a5 = " << dh.a[4] << " (need 0)";
  if (std::abs(dh.a[1]) < kTol) bad << " a2 = 0";
  if (std::abs(dh.a[2]) < kTol) bad << " a3 = 0";
  return bad.str();
}

}  // namespace wysiwyf::robot::detail
