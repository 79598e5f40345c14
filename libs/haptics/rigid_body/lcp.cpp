#include "rigid_body/lcp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wysiwyf::haptics {

namespace {
// kDependent: not clamped, and kept out of the clamped set while it stays as it is (see solve_small).
constexpr char kUnset = 0, kClamped = 1, kNotClamped = 2, kDependent = 3;

// The largest |entry| of A or b, for judging round-off against (never 0 for A: it divides).
double scale_of(const LcpMatrix& A) { return std::max(A.size() ? A.cwiseAbs().maxCoeff() : 0.0, 1e-300); }
double scale_of(const LcpVector& b) { return b.size() ? b.cwiseAbs().maxCoeff() : 0.0; }

template <typename Matrix, typename Vector>
bool solve_ldlt(const Matrix& Acc, const Vector& rhs, Vector& x) {
  const Eigen::LDLT<Matrix> ldlt(Acc);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return false;
  const double smallest = ldlt.vectorD().cwiseAbs().minCoeff();
  const double largest = ldlt.vectorD().cwiseAbs().maxCoeff();
  if (!(smallest > 1e-12 * largest)) return false;
  x = ldlt.solve(rhs);
  return true;
}

// The same with a fixed-size matrix, which Eigen unrolls: the common small clamped sets (a
// resting face holds three of its four corners) cost a fraction of the general code.
template <int N>
bool solve_ldlt_fixed(const LcpMatrix& Acc, const LcpVector& rhs, LcpVector& x) {
  const Eigen::Matrix<double, N, N> A = Acc;
  const Eigen::Matrix<double, N, 1> b = rhs;
  Eigen::Matrix<double, N, 1> y;
  if (!solve_ldlt(A, b, y)) return false;
  x = y;
  return true;
}

// Solves A_CC x = rhs. The clamped set is kept non-singular, so a Cholesky (LDLT) factorisation
// does; where round-off made it singular after all, the minimum-norm solution of a complete
// orthogonal decomposition.
LcpVector solve_clamped(const LcpMatrix& Acc, const LcpVector& rhs) {
  LcpVector x;
  bool ok = false;
  switch (Acc.rows()) {
    case 1: ok = solve_ldlt_fixed<1>(Acc, rhs, x); break;
    case 2: ok = solve_ldlt_fixed<2>(Acc, rhs, x); break;
    case 3: ok = solve_ldlt_fixed<3>(Acc, rhs, x); break;
    case 4: ok = solve_ldlt_fixed<4>(Acc, rhs, x); break;
    default: ok = solve_ldlt(Acc, rhs, x);
  }
  return ok ? x : LcpVector(Acc.completeOrthogonalDecomposition().solve(rhs));
}
}  // namespace

double LcpResult::residual() const {
  double r = 0;
  for (Eigen::Index i = 0; i < f.size(); ++i) r = std::max(r, std::abs(std::min(f[i], a[i])));
  return r;
}

// Clamped sets up to this size are factorised afresh for each solve, unrolled (solve_clamped);
// beyond it the factor is kept up to date pivot by pivot.
constexpr std::size_t kSmallSet = 4;
// The floor of a pivot of the kept factor, relative to A's scale: as the fresh factorisation's
// test of its smallest pivot against its largest.
constexpr double kPivotFloor = 1e-12;

bool LcpSolver::factored() const {
  return !factor_failed_ && clamped_.size() > kSmallSet && factor_.size() == static_cast<int>(clamped_.size());
}

// x with A_CC x_C = rhs_C on the clamped set C, zero elsewhere.
LcpVector LcpSolver::on_clamped_set(const LcpMatrix& A, const LcpVector& rhs) const {
  LcpVector x = LcpVector::Zero(A.rows());
  const auto nc = static_cast<Eigen::Index>(clamped_.size());
  if (nc == 0) return x;
  LcpVector rhs_c(nc);
  for (Eigen::Index i = 0; i < nc; ++i) rhs_c[i] = rhs[clamped_[i]];
  LcpVector x_c;
  if (factored()) {
    factor_.solve(rhs_c);
    x_c = rhs_c;
  } else {
    LcpMatrix Acc(nc, nc);
    for (Eigen::Index i = 0; i < nc; ++i)
      for (Eigen::Index j = 0; j < nc; ++j) Acc(i, j) = A(clamped_[i], clamped_[j]);
    x_c = solve_clamped(Acc, rhs_c);
  }
  for (Eigen::Index i = 0; i < nc; ++i) x[clamped_[i]] = x_c[i];
  return x;
}

const LcpVector& LcpSolver::forward_column(const LcpMatrix& A, int i) {
  if (column_of_ != i) {
    const auto nc = static_cast<Eigen::Index>(clamped_.size());
    column_.resize(nc);
    for (Eigen::Index k = 0; k < nc; ++k) column_[k] = A(clamped_[k], i);
    factor_.forward(column_);
    column_of_ = i;
  }
  return column_;
}

// The force direction that keeps every clamped contact's acceleration at zero while f_d grows by 1.
LcpVector LcpSolver::direction(const LcpMatrix& A, int d) {
  if (!factored()) {
    LcpVector df = on_clamped_set(A, -A.col(d));
    df[d] = 1;
    return df;
  }
  LcpVector x_c = forward_column(A, d);  // (kept: d is often clamped next, C unchanged)
  factor_.back(x_c);
  LcpVector df = LcpVector::Zero(A.rows());
  for (std::size_t k = 0; k < clamped_.size(); ++k) df[clamped_[k]] = -x_c[static_cast<Eigen::Index>(k)];
  df[d] = 1;
  return df;
}

// Whether contact i's row depends on the clamped ones': the Schur complement of A_CC in
// A_{C+i, C+i} (the acceleration i would get from a unit force of its own with the clamped
// contacts held) below round-off of A's scale. With the factor that is A_ii - |L^-1 A(C, i)|^2.
bool LcpSolver::dependent(const LcpMatrix& A, int i, double scale_A) {
  if (factored()) return A(i, i) - forward_column(A, i).squaredNorm() <= 1e-10 * scale_A;
  const LcpVector x = on_clamped_set(A, A.col(i));
  return A(i, i) - A.col(i).dot(x) <= 1e-10 * scale_A;
}

void LcpSolver::clamp(const LcpMatrix& A, int i, double scale_A) {
  if (!factor_failed_ && clamped_.size() >= kSmallSet) {  // C grows beyond the small sets
    const bool kept = factor_.size() == static_cast<int>(clamped_.size());
    if (kept && !factor_.append(forward_column(A, i), A(i, i), kPivotFloor * scale_A)) factor_failed_ = true;
    clamped_.push_back(i);
    column_of_ = -1;
    if (!kept) factorise(A, scale_A);  // it has just outgrown them: its factor, once
    return;
  }
  clamped_.push_back(i);
  column_of_ = -1;
  if (!factor_failed_) factor_.clear();  // (a small set is factorised afresh for each solve: no stale rows)
}

void LcpSolver::release(int i) {
  const auto at = std::find(clamped_.begin(), clamped_.end(), i);
  const bool kept = !factor_failed_ && factor_.size() == static_cast<int>(clamped_.size());
  if (kept) factor_.remove(static_cast<int>(at - clamped_.begin()));
  clamped_.erase(at);
  column_of_ = -1;
}

void LcpSolver::factorise(const LcpMatrix& A, double scale_A) {
  factor_.clear();
  column_of_ = -1;
  const auto nc = static_cast<Eigen::Index>(clamped_.size());
  if (factor_failed_ || static_cast<std::size_t>(nc) <= kSmallSet) return;
  LcpVector l;
  for (Eigen::Index t = 0; t < nc; ++t) {
    const int i = clamped_[static_cast<std::size_t>(t)];
    l.resize(t);
    for (Eigen::Index k = 0; k < t; ++k) l[k] = A(clamped_[static_cast<std::size_t>(k)], i);
    factor_.forward(l);
    if (!factor_.append(l, A(i, i), kPivotFloor * scale_A)) {
      factor_failed_ = true;
      return;
    }
  }
}

// With redundant contacts the forces are not unique, and the pivoting path can leave large
// opposing forces that cancel (a squeeze), whose round-off spoils a = A f + b. The minimum-norm
// forces of the final clamped set carry no such squeeze; they replace the pivoting result when
// they are still a solution.
void LcpSolver::polish(const LcpMatrix& A, const LcpVector& b, LcpResult& r) {
  if (clamped_.empty()) return;
  const LcpVector f = on_clamped_set(A, -b);
  const LcpVector a = A * f + b;
  const double tol = 1e-12 * std::max(1.0, b.cwiseAbs().maxCoeff());
  if (f.minCoeff() < -tol || a.minCoeff() < -tol) return;  // not a solution: keep the pivoting one
  if (f.cwiseAbs().maxCoeff() < r.f.cwiseAbs().maxCoeff()) r.f = f;
}

namespace {
void check_size(Eigen::Index n) {
  if (n > kMaxLcpSize)
    throw std::length_error("LCP with " + std::to_string(n) + " contacts; at most " + std::to_string(kMaxLcpSize) +
                            " are supported");
}
}  // namespace

LcpResult LcpSolver::solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  check_size(b.size());
  return solve_small(A, b);
}

LcpResult LcpSolver::solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const LcpIndices& warm_start) {
  check_size(b.size());
  const LcpMatrix As = A;
  const LcpVector bs = b;
  const Eigen::Index n = b.size();
  state_.assign(static_cast<std::size_t>(n), kNotClamped);
  clamped_.clear();
  for (const int i : warm_start) {
    if (i < 0 || i >= n || state_[static_cast<std::size_t>(i)] == kClamped) {  // not a set of this problem
      clamped_.clear();
      break;
    }
    state_[static_cast<std::size_t>(i)] = kClamped;
    clamped_.push_back(i);
  }
  LcpResult r;
  if (!clamped_.empty()) {
    factor_failed_ = false;
    factorise(As, scale_of(As));  // (or, where it cannot, A_CC factorised afresh for the solve)
    if (solve_on_clamped_set(As, bs, r)) return r;
    // Not a solution: the pivoting goes on from what of the set still holds (from nothing, a
    // pushed pile's island would pivot through most of its contacts again).
    if (start_from_clamped_set(As, bs, r)) {
      LcpResult warm = drive(As, bs, r);
      if (warm.ok) return warm;  // (else from nothing: a start that cycles is no reason to fail)
    }
  }
  return solve_small(As, bs);
}

bool LcpSolver::start_from_clamped_set(const LcpMatrix& A, const LcpVector& b, LcpResult& r) {
  if (factor_failed_) return false;  // (A_CC is not positive definite: no kept factor to go on with)
  const Eigen::Index n = b.size();
  // The clamped contacts whose forces come out negative leave the set until none does: then the
  // clamped ones hold at zero acceleration with forces >= 0, the invariant the pivoting keeps.
  for (bool dropped = true; dropped;) {
    r.f = on_clamped_set(A, -b);
    dropped = false;
    for (Eigen::Index i = 0; i < n; ++i)
      if (state_[static_cast<std::size_t>(i)] == kClamped && r.f[i] < 0) {
        state_[static_cast<std::size_t>(i)] = kUnset;
        release(static_cast<int>(i));
        dropped = true;
      }
    if (factor_failed_) return false;
  }
  r.a = A * r.f + b;
  const double tol = accel_tolerance(scale_of(A), scale_of(b), r.f);
  // The others: satisfied where they do not close, else driven to complementarity as from nothing.
  for (Eigen::Index i = 0; i < n; ++i) {
    auto& s = state_[static_cast<std::size_t>(i)];
    if (s == kClamped) {
      if (std::abs(r.a[i]) > tol) return false;  // A_CC singular after all (a small set's fresh solve)
      r.a[i] = 0;
    } else
      s = r.a[i] >= -tol ? kNotClamped : kUnset;
  }
  return true;
}

bool LcpSolver::solve_on_clamped_set(const LcpMatrix& A, const LcpVector& b, LcpResult& r) {
  const Eigen::Index n = b.size();
  r.f = on_clamped_set(A, -b);
  r.a = A * r.f + b;
  // The same judgement of round-off as the pivoting method's.
  const double scale_A = scale_of(A);
  const double tol = accel_tolerance(scale_A, scale_of(b), r.f);
  const double f_tol = tol / scale_A;
  bool negative = false;  // round-off below zero, cleaned as the pivoting method does
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool in_c = state_[static_cast<std::size_t>(i)] == kClamped;
    if (in_c ? (r.f[i] < -f_tol || std::abs(r.a[i]) > tol) : r.a[i] < -tol) return false;
    negative = negative || r.f[i] < 0;
  }
  if (negative) {
    r.f = r.f.cwiseMax(0.0);
    r.a = A * r.f + b;
  }
  r.clamped = Eigen::Map<const LcpIndices>(clamped_.data(), static_cast<Eigen::Index>(clamped_.size()));
  r.warm = r.ok = true;
  return true;
}

LcpResult LcpSolver::solve_small(const LcpMatrix& A, const LcpVector& b) {
  const Eigen::Index n = b.size();
  LcpResult r;
  r.f = LcpVector::Zero(n);
  r.a = b;
  clamped_.clear();
  factor_.clear();
  factor_failed_ = false;
  column_of_ = -1;
  state_.assign(static_cast<std::size_t>(n), kUnset);
  return drive(A, b, r);
}

LcpResult LcpSolver::drive(const LcpMatrix& A, const LcpVector& b, LcpResult& r) {
  const Eigen::Index n = b.size();
  const double scale_A = scale_of(A);
  const double scale_b = scale_of(b);
  const int max_pivots = static_cast<int>(50 * n + 100);  // a guard against cycling
  // Round-off in a = A f + b grows with the forces; "satisfied" and "blocking" are judged against it.
  auto accel_tolerance = [&] { return this->accel_tolerance(scale_A, scale_b, r.f); };

  for (Eigen::Index d = 0; d < n; ++d) {
    if (state_[d] != kUnset) continue;   // (a warm start's: clamped, or satisfied)
    if (r.a[d] >= -accel_tolerance()) {  // already satisfied with f_d = 0
      state_[d] = kNotClamped;
      continue;
    }
    // Drive a_d to zero (Baraff's drive-to-zero).
    while (true) {
      if (++r.pivots > max_pivots) return r;
      const LcpVector df = direction(A, static_cast<int>(d));
      const LcpVector da = A * df;
      // A change smaller than this is round-off: it neither blocks nor moves a_d. Judging it so
      // keeps dependent contacts out of the clamped set, which then stays non-singular (Baraff's
      // argument for the frictionless case).
      const double df_scale = df.cwiseAbs().maxCoeff();
      const double da_eps = 1e-10 * scale_A * df_scale;
      const double df_eps = 1e-10 * df_scale;
      double step = std::numeric_limits<double>::infinity();
      Eigen::Index blocking = -1;
      if (da[d] > da_eps) {
        step = -r.a[d] / da[d];
        blocking = d;
      }
      for (Eigen::Index i = 0; i < n; ++i) {
        if (i == d) continue;
        if (state_[i] == kClamped && df[i] < -df_eps) {
          const double s = -r.f[i] / df[i];
          if (s < step) step = s, blocking = i;
        } else if (state_[i] == kNotClamped && da[i] < -da_eps) {
          const double s = -r.a[i] / da[i];
          if (s < step) step = s, blocking = i;
        }
      }
      if (blocking < 0) {
        // Nothing blocks and a_d does not move: d depends on the clamped contacts, and in exact
        // arithmetic a_d is then already 0 (Baraff 1994, section 5); what is left is round-off.
        if (r.a[d] >= -1e3 * accel_tolerance()) {
          r.a[d] = 0;
          state_[d] = kNotClamped;
          break;
        }
        return r;  // unbounded: A is not PSD on this set, or b is infeasible
      }
      // A contact about to be clamped whose row is (within round-off of the factorisation) a
      // combination of the clamped ones' would make A_CC singular: the next directions would be
      // noise, and with them the pivoting cycles (a face pressed from both sides, the normals of
      // its contacts a few 1e-7 rad apart, released and clamped again for ever). Its acceleration
      // follows the clamped ones' (to those 1e-7): it is left out while the clamped set stands.
      if (blocking != d && state_[blocking] == kNotClamped && dependent(A, static_cast<int>(blocking), scale_A)) {
        state_[blocking] = kDependent;
        continue;
      }
      step = std::max(step, 0.0);
      r.f += step * df;
      r.a += step * da;
      if (blocking == d) {
        r.a[d] = 0;
        state_[d] = kClamped;
        clamp(A, static_cast<int>(d), scale_A);
        break;
      }
      if (state_[blocking] == kClamped) {  // its force reached zero: release it
        r.f[blocking] = 0;
        state_[blocking] = kNotClamped;
        release(static_cast<int>(blocking));
        std::replace(state_.begin(), state_.end(), kDependent, kNotClamped);  // (a smaller set: look again)
      } else {                                                                // its acceleration reached zero: clamp it
        r.a[blocking] = 0;
        state_[blocking] = kClamped;
        clamp(A, static_cast<int>(blocking), scale_A);
      }
    }
  }
  std::replace(state_.begin(), state_.end(), kDependent, kNotClamped);
  polish(A, b, r);
  // Clean round-off: forces never negative, accelerations consistent with them.
  for (Eigen::Index i = 0; i < n; ++i) r.f[i] = std::max(r.f[i], 0.0);
  r.a = A * r.f + b;
  r.clamped = Eigen::Map<const LcpIndices>(clamped_.data(), static_cast<Eigen::Index>(clamped_.size()));
  r.ok = true;
  return r;
}

}  // namespace wysiwyf::haptics
