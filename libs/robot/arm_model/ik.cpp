// ArmModel's inverse kinematics: the dispatch to the closed form of the chain (PumaModel's for
// the PUMA 560, ur_ik for UR-type arms) or the numerical search, the 2 pi representative of
// each angle, and the nearest solution within limits.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "arm_model/arm_model.hpp"
#include "arm_model/ur_ik.hpp"
#include "puma_model/puma_model.hpp"

namespace wysiwyf::robot {
namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kLimitTolerance = 1e-12;  // rad, on joint limits

// The 2 pi representative of `a` inside [lo, hi] nearest to `ref`; when none lies inside, the
// one nearest to `ref` and inside = false.
double wrap_into(double a, double lo, double hi, double ref, bool& inside) {
  const double nearest = a + kTwoPi * std::round((ref - a) / kTwoPi);
  if (nearest >= lo - kLimitTolerance && nearest <= hi + kLimitTolerance) return nearest;
  double best = nearest;
  bool found = false;
  for (double c = a + kTwoPi * std::ceil((lo - kLimitTolerance - a) / kTwoPi); c <= hi + kLimitTolerance; c += kTwoPi) {
    if (!found || std::abs(c - ref) < std::abs(best - ref)) best = c;
    found = true;
  }
  if (!found) inside = false;
  return best;
}

}  // namespace

const char* to_string(ArmIkStatus status) {
  switch (status) {
    case ArmIkStatus::kOk: return "ok";
    case ArmIkStatus::kInvalidInput: return "invalid input (non-finite pose or joint vector)";
    case ArmIkStatus::kOutOfReach: return "out of reach (no branch of the closed form reaches the pose)";
    case ArmIkStatus::kJointLimits: return "reachable only outside the joint limits";
    case ArmIkStatus::kNotFound: return "no solution found within limits (out of reach, or missed by every seed)";
  }
  return "unknown";
}

void ArmModel::add_solution(ArmIkSolutions& out, const JointVector& q, const JointRef& q_ref, int branch,
                            bool singular) const {
  const int n = dof();
  ArmIkSolution sol;
  sol.q.resize(n);
  bool inside = true;
  for (int j = 0; j < n; ++j) {
    const JointKind kind = joints_[static_cast<std::size_t>(j)].kind;
    if (kind == JointKind::kPrismatic) {
      sol.q[j] = q[j];
      inside = inside && q[j] >= limits_.lower[j] - kLimitTolerance && q[j] <= limits_.upper[j] + kLimitTolerance;
    } else if (kind == JointKind::kContinuous) {
      sol.q[j] = q[j] + kTwoPi * std::round((q_ref[j] - q[j]) / kTwoPi);
    } else {
      sol.q[j] = wrap_into(q[j], limits_.lower[j], limits_.upper[j], q_ref[j], inside);
    }
  }
  for (int i = 0; i < out.count; ++i)
    if ((out.solution[static_cast<std::size_t>(i)].q - sol.q).cwiseAbs().maxCoeff() < ik_options_.duplicate) return;
  if (out.count == kMaxIkSolutions) return;
  sol.within_limits = inside;
  sol.singular = singular;
  sol.branch = branch;
  out.solution[static_cast<std::size_t>(out.count++)] = sol;
  if (inside) ++out.within_limits_count;
}

ArmIkSolutions ArmModel::ik(const Eigen::Isometry3d& base_T_frame, const JointRef& q_ref, FrameId f) const {
  const Frame& fr = frames_[check(f)];
  check_size(q_ref, "q_ref");
  if (fr.body != dof())
    throw std::invalid_argument("ArmModel::ik: frame '" + fr.name + "' is not fixed to the last link");
  ArmIkSolutions out;
  out.method = ik_method_;
  if (!base_T_frame.matrix().allFinite() || !q_ref.allFinite()) return out;  // kInvalidInput
  switch (ik_method_) {
    case ArmIkMethod::kPumaClosedForm: return ik_puma(base_T_frame, q_ref, f);
    case ArmIkMethod::kUrClosedForm: return ik_closed_form(base_T_frame * fr.body_T_frame.inverse(), q_ref);
    case ArmIkMethod::kNumerical: return ik_numerical(base_T_frame, q_ref, f);
  }
  return out;
}

ArmIkSolutions ArmModel::ik_puma(const Eigen::Isometry3d& base_T_frame, const JointRef& q_ref, FrameId f) const {
  ArmIkSolutions out;
  out.method = ArmIkMethod::kPumaClosedForm;
  const IkSolutions all = puma_->ik(base_T_frame, Vector6d(q_ref), puma_frames_[check(f)]);
  for (int i = 0; i < 8; ++i) {
    const IkSolution& sol = all.solution[static_cast<std::size_t>(i)];
    if (sol.valid) add_solution(out, JointVector(sol.q), q_ref, i, sol.wrist_singular);
  }
  out.status = out.within_limits_count > 0 ? ArmIkStatus::kOk
               : out.count > 0             ? ArmIkStatus::kJointLimits
                                           : ArmIkStatus::kOutOfReach;
  if (all.status == IkStatus::kInvalidInput) out.status = ArmIkStatus::kInvalidInput;
  return out;
}

ArmIkSolutions ArmModel::ik_closed_form(const Eigen::Isometry3d& base_T_body, const JointRef& q_ref) const {
  ArmIkSolutions out;
  out.method = ArmIkMethod::kUrClosedForm;
  const Eigen::Isometry3d dh0_T_dh6 = dh_.base_T_dh0.inverse() * base_T_body * dh_.dhn_T_body.inverse();
  std::array<detail::UrBranch, 8> branches;
  detail::ur_ik(dh_, dh0_T_dh6, q_ref[5] + dh_.offset[5], branches);
  JointVector q(6);
  for (int i = 0; i < 8; ++i) {
    const detail::UrBranch& b = branches[static_cast<std::size_t>(i)];
    if (!b.valid) continue;
    for (int j = 0; j < 6; ++j) q[j] = b.theta[static_cast<std::size_t>(j)] - dh_.offset[static_cast<std::size_t>(j)];
    add_solution(out, q, q_ref, i, b.singular);
  }
  out.status = out.within_limits_count > 0 ? ArmIkStatus::kOk
               : out.count > 0             ? ArmIkStatus::kJointLimits
                                           : ArmIkStatus::kOutOfReach;
  return out;
}

ArmIkResult ArmModel::ik_nearest(const Eigen::Isometry3d& base_T_frame, const JointRef& q_current, FrameId f) const {
  const Frame& fr = frames_[check(f)];
  check_size(q_current, "q_current");
  if (fr.body != dof())
    throw std::invalid_argument("ArmModel::ik_nearest: frame '" + fr.name + "' is not fixed to the last link");
  ArmIkResult result;
  if (!base_T_frame.matrix().allFinite() || !q_current.allFinite()) return result;  // kInvalidInput
  if (ik_method_ == ArmIkMethod::kNumerical) {
    // The q_current seed, pulled towards q_current in the null space: along a path this is the
    // continuous solution, so it is taken at once when it stays near.
    JointVector q;
    if (solve_numerical(base_T_frame, f, JointVector(q_current), q_current, q)) {
      ArmIkSolutions one;
      add_solution(one, q, q_current, 0, false);
      const ArmIkSolution& sol = one.solution[0];
      if (sol.within_limits && (sol.q - q_current).norm() <= ik_options_.local_radius) {
        result.status = ArmIkStatus::kOk;
        result.q = sol.q;
        result.branch = 0;
        return result;
      }
    }
  }
  const ArmIkSolutions all = ik(base_T_frame, q_current, f);
  result.status = all.status;
  if (all.status != ArmIkStatus::kOk) return result;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < all.count; ++i) {
    const ArmIkSolution& sol = all.solution[static_cast<std::size_t>(i)];
    if (!sol.within_limits) continue;
    const double d = (sol.q - q_current).squaredNorm();
    if (d < best) {
      best = d;
      result.q = sol.q;
      result.branch = sol.branch;
      result.singular = sol.singular;
    }
  }
  return result;
}

}  // namespace wysiwyf::robot
