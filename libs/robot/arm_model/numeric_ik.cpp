// Numerical inverse kinematics for chains without a closed form (7-joint arms, any URDF):
// Levenberg-Marquardt on the pose error with the joints clamped to their limits, from q_ref
// and then from deterministic seeds spread over the limits; for redundant arms, steps in the
// null space of the Jacobian towards q_ref, each followed by re-converging on the pose, so a
// solution is the locally nearest one to q_ref on its self-motion manifold and stays
// continuous along a path. Where q_ref lies near a position limit, the goal is q_ref moved a
// little (limit_push) towards the limit's inner margin (limit_margin): along a path the
// redundancy turns the arm away from its limits instead of running into them.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "arm_model/arm_model.hpp"
#include "puma_model/rigid.hpp"

namespace wysiwyf::robot {
namespace {

using detail::kPi;
constexpr double kBaseDamping = 1e-9;  // lambda^2 floor of the LM step [m^2 or rad^2]

using detail::pose_error;

// The largest |v_j| (a plain loop: GCC's warning on Eigen's vectorised reduction over a
// fixed-capacity vector is a false positive).
double max_abs(const JointVector& v) {
  double m = 0.0;
  for (Eigen::Index j = 0; j < v.size(); ++j) m = std::max(m, std::abs(v[j]));
  return m;
}

bool small(const Vector6d& e, double tolerance) {
  return e.head<3>().norm() < tolerance && e.tail<3>().norm() < tolerance;
}

// The i-th element of the van der Corput sequence in `base` (the Halton sequence's coordinates).
double radical_inverse(int i, int base) {
  double result = 0.0, f = 1.0 / base;
  for (; i > 0; i /= base, f /= base) result += f * (i % base);
  return result;
}

}  // namespace

void ArmModel::make_seeds() {
  static constexpr int kPrimes[kMaxArmDof] = {2, 3, 5, 7, 11, 13, 17, 19};
  const int n = dof();
  seeds_.clear();
  for (int k = 1; k <= ik_options_.seeds; ++k) {
    JointVector q(n);
    for (int j = 0; j < n; ++j) {
      const bool bounded = std::isfinite(limits_.lower[j]) && std::isfinite(limits_.upper[j]);
      const double lo = bounded ? limits_.lower[j] : -kPi, hi = bounded ? limits_.upper[j] : kPi;
      q[j] = lo + (hi - lo) * radical_inverse(k, kPrimes[j]);
    }
    seeds_.push_back(q);
  }
}

void ArmModel::set_ik_options(const ArmIkOptions& options) {
  ik_options_ = options;
  make_seeds();
}

bool ArmModel::converge(const Eigen::Isometry3d& target, FrameId f, JointVector& q, int& budget) const {
  const ArmIkOptions& o = ik_options_;
  Vector6d e = pose_error(target, fk(q, f));
  double mu = 1.0;
  Eigen::LDLT<Matrix6d> ldlt;
  while (budget-- > 0) {
    if (small(e, o.tolerance)) return true;
    const ArmJacobian J = jacobian(q, f);
    const Matrix6d JJt = J * J.transpose();
    const double err2 = e.squaredNorm();
    // Retry the same linearisation with more damping until a step lowers the error.
    while (true) {
      ldlt.compute(JJt + mu * (kBaseDamping + 0.5 * err2) * Matrix6d::Identity());
      JointVector dq = J.transpose() * ldlt.solve(e);
      const double largest = max_abs(dq);
      if (largest > o.max_step) dq *= o.max_step / largest;
      const JointVector q_try = (q + dq).cwiseMax(limits_.lower).cwiseMin(limits_.upper);
      const Vector6d e_try = pose_error(target, fk(q_try, f));
      if (e_try.squaredNorm() < err2) {
        q = q_try;
        e = e_try;
        mu = std::max(mu * 0.1, 1.0);
        break;
      }
      mu *= 10.0;
      if (mu > 1e12 || budget-- <= 0) return false;  // stuck (a limit, a local minimum)
    }
  }
  return small(e, o.tolerance);
}

bool ArmModel::solve_numerical(const Eigen::Isometry3d& target, FrameId f, const JointVector& seed,
                               const JointRef& q_goal, JointVector& q) const {
  const ArmIkOptions& o = ik_options_;
  int budget = o.max_iterations;
  q = seed.cwiseMax(limits_.lower).cwiseMin(limits_.upper);
  if (!converge(target, f, q, budget)) return false;
  if (dof() <= 6) return true;
  // Redundancy: move along the self-motion manifold towards q_goal, nudged away from the limits.
  JointVector goal(dof());
  for (int j = 0; j < dof(); ++j) {
    const double margin = std::min(o.limit_margin, 0.25 * (limits_.upper[j] - limits_.lower[j]));
    const double inner = std::clamp(q_goal[j], limits_.lower[j] + margin, limits_.upper[j] - margin);
    goal[j] = std::clamp(q_goal[j] + std::clamp(inner - q_goal[j], -o.limit_push, o.limit_push), limits_.lower[j],
                         limits_.upper[j]);
  }
  Eigen::LDLT<Matrix6d> ldlt;
  double scale = o.null_gain;
  while (budget > 0) {
    const ArmJacobian J = jacobian(q, f);
    const JointVector z = goal - q;
    ldlt.compute(J * J.transpose() + kBaseDamping * Matrix6d::Identity());
    JointVector dq = scale * (z - J.transpose() * ldlt.solve(J * z));
    const double largest = max_abs(dq);
    if (largest < o.null_tolerance) return true;
    if (largest > o.max_step) dq *= o.max_step / largest;
    JointVector q_try = (q + dq).cwiseMax(limits_.lower).cwiseMin(limits_.upper);
    if (converge(target, f, q_try, budget) && (q_try - goal).squaredNorm() < (q - goal).squaredNorm()) {
      q = q_try;
      scale = std::min(o.null_gain, 2.0 * scale);
    } else {
      scale *= 0.5;
      if (scale * largest < o.null_tolerance) return true;
    }
  }
  return true;  // a solution, nearer q_goal than the seed's but short of the nearest
}

ArmIkSolutions ArmModel::ik_numerical(const Eigen::Isometry3d& base_T_frame, const JointRef& q_ref, FrameId f) const {
  ArmIkSolutions out;
  out.method = ArmIkMethod::kNumerical;
  JointVector q;
  if (solve_numerical(base_T_frame, f, JointVector(q_ref), q_ref, q)) add_solution(out, q, q_ref, 0, false);
  for (std::size_t k = 0; k < seeds_.size() && out.count < kMaxIkSolutions; ++k)
    if (solve_numerical(base_T_frame, f, seeds_[k], q_ref, q))
      add_solution(out, q, q_ref, static_cast<int>(k) + 1, false);
  out.status = out.count > 0 ? ArmIkStatus::kOk : ArmIkStatus::kNotFound;
  return out;
}

}  // namespace wysiwyf::robot
