// Closed-form IK of a UR-type arm, derived for A_i = Rz(t_i) Tz(d_i) Tx(a_i) Rx(alpha_i) with
// alpha = (90, 0, 0, 90, -90, 0) deg and a4 = a5 = a6 = 0 (T = dh0_T_dh6 = A1 ... A6):
//
// Axes 2, 3, 4 are parallel to z1 = (s1, -c1, 0), and frame 1's origin (a1 c1, a1 s1, d1) has
// no z1 component. In frame 1 the origin of frame 5 sits at height D = d2 + d3 + d4 along z1
// (d5 runs along z4, which is normal to z1), and p05 = p06 - d6 z6, so
//   p05x s1 - p05y c1 = D  ->  t1 = phi + asin(D / rho) or phi + pi - asin(D / rho),
// phi = atan2(p05y, p05x), rho = |p05xy| >= |D|.
// The rotation from frame 1 to 6 is R16 = Rz(t2 + t3 + t4) Ry(-t5) Rz(t6), so
//   z6 . z1 = cos t5                     ->  t5 = +-acos(z6 . z1),
//   z1 in frame 6 = (c6 s5, -s6 s5, c5)  ->  t6 = atan2(-(y6 . z1) / s5, (x6 . z1) / s5).
// Then T14 = A1^-1 T A6^-1 A5^-1 is the planar 3R part: its origin (x, y) = a2 (c2, s2) +
// a3 (c23, s23) gives t3 = +-acos((x^2 + y^2 - a2^2 - a3^2) / (2 a2 a3)) and
// t2 = atan2(y, x) - atan2(a3 s3, a2 + a3 c3); its rotation Rz(t234) Rx(90) gives t4.
#include "arm_model/ur_ik.hpp"

#include <algorithm>
#include <cmath>

#include "puma_model/rigid.hpp"

namespace wysiwyf::robot::detail {
namespace {

constexpr double kReach = 1e-10;     // on the sine/cosine arguments that must stay within [-1, 1]
constexpr double kSingular = 1e-10;  // |sin t5| below this: wrist singularity

}  // namespace

void ur_ik(const DhChain& dh, const Eigen::Isometry3d& T, double theta6_ref, std::array<UrBranch, 8>& out) {
  for (UrBranch& b : out) b = UrBranch{};
  const Eigen::Matrix3d& R = T.linear();
  const Eigen::Vector3d z6 = R.col(2);
  const Eigen::Vector3d p05 = T.translation() - dh.d[5] * z6;
  const double D = dh.d[1] + dh.d[2] + dh.d[3];
  const double rho = std::hypot(p05.x(), p05.y());
  if (rho < std::abs(D) * (1.0 - kReach) || rho < 1e-300) return;
  const double phi = std::atan2(p05.y(), p05.x());
  const double psi = std::asin(std::clamp(D / rho, -1.0, 1.0));
  const double a2 = dh.a[1], a3 = dh.a[2];

  for (int shoulder = 0; shoulder < 2; ++shoulder) {
    const double t1 = shoulder ? phi + kPi - psi : phi + psi;
    const Eigen::Vector3d z1(std::sin(t1), -std::cos(t1), 0.0);
    const double c5 = std::clamp(z6.dot(z1), -1.0, 1.0);
    const double s5_abs = z6.cross(z1).norm();
    for (int wrist = 0; wrist < 2; ++wrist) {
      const double s5 = wrist ? -s5_abs : s5_abs;
      const double t5 = std::atan2(s5, c5);
      const bool singular = s5_abs < kSingular;
      const double t6 =
          singular ? theta6_ref
                   : std::atan2(-R.col(1).dot(z1) * (s5 > 0 ? 1.0 : -1.0), R.col(0).dot(z1) * (s5 > 0 ? 1.0 : -1.0));
      const Eigen::Isometry3d T14 = dh_transform(t1, dh.d[0], dh.a[0], dh.alpha[0]).inverse() * T *
                                    dh_transform(t6, dh.d[5], dh.a[5], dh.alpha[5]).inverse() *
                                    dh_transform(t5, dh.d[4], dh.a[4], dh.alpha[4]).inverse();
      const double x = T14.translation().x(), y = T14.translation().y();
      const double c3 = (x * x + y * y - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
      if (std::abs(c3) > 1.0 + kReach) continue;
      const double c3c = std::clamp(c3, -1.0, 1.0);
      const double s3_abs = std::sqrt(1.0 - c3c * c3c);
      const double t234 = std::atan2(T14.linear()(1, 0), T14.linear()(0, 0));
      for (int elbow = 0; elbow < 2; ++elbow) {
        const double s3 = elbow ? -s3_abs : s3_abs;
        const double t3 = std::atan2(s3, c3c);
        const double t2 = std::atan2(y, x) - std::atan2(a3 * s3, a2 + a3 * c3c);
        UrBranch& b = out[static_cast<std::size_t>(shoulder + 2 * wrist + 4 * elbow)];
        b.theta = {t1, t2, t3, t234 - t2 - t3, t5, t6};
        b.valid = true;
        b.singular = singular;
      }
    }
  }
}

}  // namespace wysiwyf::robot::detail
