// Closed-form inverse kinematics of the PUMA 560 (spherical wrist), derived for the DH geometry
// read from the URDF (PumaModel::derive_ik_constants checks it):
//
//   dh0_T_link6 = A1(q1) ... A5(q5) Rz(q6), A_i = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i),
//   alpha = (90, 0, -90, 90, -90) deg, a4 = a5 = d5 = 0.
//
// Wrist centre (origin of link 6) in DH frame 0, with D = d2 + d3, h = pz - d1:
//   px = c1 r + s1 D,  py = s1 r - c1 D,   r = a1 + a2 c2 + a3 c23 - d4 s23,
//   h  = a2 s2 + a3 s23 + d4 c23.
// So px s1 - py c1 = D: q1 = atan2(py, px) + atan2(D, r), r = +-sqrt(px^2 + py^2 - D^2).
// In the arm plane (x1 = r - a1, h) the forearm is a link of length L3 = hypot(a3, d4) at
// angle q23 + beta, beta = atan2(d4, a3):
//   cos(q3 + beta) = (x1^2 + h^2 - a2^2 - L3^2) / (2 a2 L3),
//   q2 = atan2(h, x1) - atan2(L3 sin(q3 + beta), a2 + L3 cos(q3 + beta)).
// Orientation: R03 = Rz(q1) Rx(90) Rz(q23) Rx(-90) = Rz(q1) Ry(-q23) and
// R36 = Rz(q4) Rx(90) Rz(q5) Rx(-90) Rz(q6) = Rz(q4) Ry(-q5) Rz(q6), so
//   R36[2][2] = c5, R36[0][2] = -c4 s5, R36[1][2] = -s4 s5, R36[2][0] = s5 c6, R36[2][1] = -s5 s6,
// q6 is taken from Ry(q5) Rz(-q4) R36 = Rz(q6); the flipped wrist is (q4 + pi, -q5, q6 + pi).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "puma_model/puma_model.hpp"
#include "puma_model/rigid.hpp"

namespace wysiwyf::robot {
namespace {

constexpr double kLimitTolerance = 1e-12;  // rad, on joint limits
constexpr double kReachTolerance = 1e-10;  // on the cosine of the elbow angle
constexpr double kWristSingular = 1e-10;   // |sin q5| below this: q4 is kept at the reference

// The 2 pi representative of `a` inside [lo, hi] nearest to `ref`; else `a` in (-pi, pi].
double wrap_into(double a, double lo, double hi, double ref, bool& inside) {
  double c = a + detail::kTwoPi * std::ceil((lo - kLimitTolerance - a) / detail::kTwoPi);
  if (c > hi + kLimitTolerance) {
    inside = false;
    return detail::wrap_to_pi(a);
  }
  double best = c;
  for (c += detail::kTwoPi; c <= hi + kLimitTolerance; c += detail::kTwoPi)
    if (std::abs(c - ref) < std::abs(best - ref)) best = c;
  return best;
}

// q6 such that Rz(q4) Ry(-q5) Rz(q6) = R36 given q4, q5 (used at the wrist singularity).
double residual_q6(const Eigen::Matrix3d& R36, double q4, double q5) {
  const double c4 = std::cos(q4), s4 = std::sin(q4);
  const double a00 = c4 * R36(0, 0) + s4 * R36(1, 0);
  const double a10 = c4 * R36(1, 0) - s4 * R36(0, 0);
  const double m00 = std::cos(q5) * a00 + std::sin(q5) * R36(2, 0);
  return std::atan2(a10, m00);
}

}  // namespace

const char* to_string(IkStatus status) {
  switch (status) {
    case IkStatus::kOk: return "ok";
    case IkStatus::kInvalidInput: return "invalid input (non-finite pose or joint vector)";
    case IkStatus::kOutOfReach: return "out of reach (wrist centre too far from or too near to the shoulder)";
    case IkStatus::kInsideShoulderCylinder:
      return "out of reach (wrist centre nearer to the joint-1 axis than the shoulder offset)";
    case IkStatus::kJointLimits: return "reachable only outside the joint limits";
  }
  return "unknown";
}

IkSolutions PumaModel::ik(const Eigen::Isometry3d& base_T_frame, const Vector6d& q_ref, FrameId f) const {
  const Frame& fr = frames_[check(f)];
  if (fr.body != kDof)
    throw std::invalid_argument("PumaModel::ik: frame '" + fr.name + "' is not fixed to the last link");
  IkSolutions out;
  if (!base_T_frame.matrix().allFinite() || !q_ref.allFinite()) return out;  // kInvalidInput

  // Pose of link 6 in DH frame 0.
  const Eigen::Matrix3d base_R_link6 = base_T_frame.linear() * fr.R.transpose();
  const Eigen::Vector3d base_p_link6 = base_T_frame.translation() - base_R_link6 * fr.p;
  const Eigen::Matrix3d Rw = ikc_.mount_R.transpose() * base_R_link6;
  const Eigen::Vector3d pw = ikc_.mount_R.transpose() * (base_p_link6 - ikc_.mount_p);

  const double D = ikc_.shoulder_offset;
  const double h = pw.z() - ikc_.d1;
  const double rr2 = pw.x() * pw.x() + pw.y() * pw.y() - D * D;
  if (rr2 < -1e-12) {
    out.status = IkStatus::kInsideShoulderCylinder;
    return out;
  }
  const double rr = std::sqrt(std::max(rr2, 0.0));
  const double rho2 = rr * rr + D * D;  // px^2 + py^2
  const double phi = std::atan2(pw.y(), pw.x());
  const double a2 = ikc_.a2, l3 = ikc_.l3, cb = ikc_.cos_beta, sb = ikc_.sin_beta;

  for (int left = 0; left < 2; ++left) {
    const double r = left ? -rr : rr;
    const double x1 = r - ikc_.a1;
    double k = (x1 * x1 + h * h - a2 * a2 - l3 * l3) / (2.0 * a2 * l3);
    if (std::abs(k) > 1.0 + kReachTolerance) continue;
    k = std::clamp(k, -1.0, 1.0);
    const double sk = std::sqrt(1.0 - k * k);
    const double q1 = phi + std::atan2(D, r);
    // cos, sin of q1 = arg((px + i py)(r + i D)), without trig.
    double c1 = 1.0, s1 = 0.0;
    if (rho2 > 1e-24) {
      c1 = (pw.x() * r - pw.y() * D) / rho2;
      s1 = (pw.y() * r + pw.x() * D) / rho2;
    }
    const double plane = std::atan2(h, x1);
    const double plane_n = std::sqrt(x1 * x1 + h * h);
    const double ux = plane_n > 1e-12 ? x1 / plane_n : 1.0, uy = plane_n > 1e-12 ? h / plane_n : 0.0;
    for (int second = 0; second < 2; ++second) {
      const double spsi = second ? -sk : sk;  // sin(q3 + beta); cos(q3 + beta) = k
      const double psi = std::atan2(spsi, k);
      const double q3 = psi - ikc_.beta;
      double gx = a2 + l3 * k, gy = l3 * spsi;  // q2 = plane - arg(gx + i gy)
      const double q2 = plane - std::atan2(gy, gx);
      const double gn = std::sqrt(gx * gx + gy * gy);
      gx = gn > 1e-12 ? gx / gn : 1.0;
      gy = gn > 1e-12 ? gy / gn : 0.0;
      // cos, sin of q23 = arg((ux + i uy)(gx - i gy)(k + i spsi)(cb - i sb)), without trig.
      const double c2 = ux * gx + uy * gy, s2 = uy * gx - ux * gy;
      const double c3 = k * cb + spsi * sb, s3 = spsi * cb - k * sb;
      const double c23 = c2 * c3 - s2 * s3, s23 = s2 * c3 + c2 * s3;
      Eigen::Matrix3d R03;
      R03 << c1 * c23, -s1, -c1 * s23, s1 * c23, c1, -s1 * s23, s23, 0.0, c23;
      const Eigen::Matrix3d R36 = R03.transpose() * Rw;

      const double s5 = std::sqrt(R36(0, 2) * R36(0, 2) + R36(1, 2) * R36(1, 2));
      const double c5 = R36(2, 2);
      const bool singular = s5 < kWristSingular;
      double q4, q5, q6, q4f, q5f, q6f;
      if (!singular) {
        // q4 from the third column; q6 from what remains of R36 after q4 and q5
        // (Ry(q5) Rz(-q4) R36 = Rz(q6)), so that near the singularity an error in q4 is
        // compensated by q6 and the pose stays exact.
        const double c4 = -R36(0, 2) / s5, s4 = -R36(1, 2) / s5;
        q4 = std::atan2(s4, c4);
        q5 = std::atan2(s5, c5);
        const double n5 = std::sqrt(s5 * s5 + c5 * c5);
        const double a00 = c4 * R36(0, 0) + s4 * R36(1, 0);
        const double a10 = c4 * R36(1, 0) - s4 * R36(0, 0);
        q6 = std::atan2(a10, (c5 * a00 + s5 * R36(2, 0)) / n5);
        q4f = q4 + detail::kPi;
        q5f = -q5;
        q6f = q6 + detail::kPi;
      } else {
        q4 = q4f = q_ref[3];
        q5 = std::atan2(s5, c5);
        q5f = -q5;
        q6 = residual_q6(R36, q4, q5);
        q6f = residual_q6(R36, q4f, q5f);
      }

      for (int flip = 0; flip < 2; ++flip) {
        IkSolution& sol = out.solution[static_cast<std::size_t>(left + 2 * second + 4 * flip)];
        const double raw[kDof] = {q1, q2, q3, flip ? q4f : q4, flip ? q5f : q5, flip ? q6f : q6};
        bool inside = true;
        for (int j = 0; j < kDof; ++j)
          sol.q[j] = wrap_into(raw[j], limits_.lower[j], limits_.upper[j], q_ref[j], inside);
        sol.valid = true;
        sol.within_limits = inside;
        sol.left_arm = left != 0;
        sol.elbow_up = (spsi < 0.0) != (left != 0);
        sol.wrist_flip = flip != 0;
        sol.wrist_singular = singular;
        ++out.valid_count;
        if (inside) ++out.within_limits_count;
      }
    }
  }
  out.status = out.within_limits_count > 0 ? IkStatus::kOk
               : out.valid_count > 0       ? IkStatus::kJointLimits
                                           : IkStatus::kOutOfReach;
  return out;
}

IkResult PumaModel::ik_nearest(const Eigen::Isometry3d& base_T_frame, const Vector6d& q_current, FrameId f) const {
  const IkSolutions all = ik(base_T_frame, q_current, f);
  IkResult result;
  result.status = all.status;
  if (all.status != IkStatus::kOk) return result;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 8; ++i) {
    const IkSolution& sol = all.solution[static_cast<std::size_t>(i)];
    if (!sol.within_limits) continue;
    const double d = (sol.q - q_current).squaredNorm();
    if (d < best) {
      best = d;
      result.q = sol.q;
      result.solution_index = i;
      result.wrist_singular = sol.wrist_singular;
    }
  }
  return result;
}

}  // namespace wysiwyf::robot
