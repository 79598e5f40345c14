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

// x with A_CC x_C = rhs_C on the clamped set C, zero elsewhere.
LcpVector LcpSolver::on_clamped_set(const LcpMatrix& A, const LcpVector& rhs) const {
  LcpVector x = LcpVector::Zero(A.rows());
  const auto nc = static_cast<Eigen::Index>(clamped_.size());
  if (nc == 0) return x;
  LcpMatrix Acc(nc, nc);
  LcpVector rhs_c(nc);
  for (Eigen::Index i = 0; i < nc; ++i) {
    rhs_c[i] = rhs[clamped_[i]];
    for (Eigen::Index j = 0; j < nc; ++j) Acc(i, j) = A(clamped_[i], clamped_[j]);
  }
  const LcpVector x_c = solve_clamped(Acc, rhs_c);
  for (Eigen::Index i = 0; i < nc; ++i) x[clamped_[i]] = x_c[i];
  return x;
}

// The force direction that keeps every clamped contact's acceleration at zero while f_d grows by 1.
LcpVector LcpSolver::direction(const LcpMatrix& A, int d) {
  LcpVector df = on_clamped_set(A, -A.col(d));
  df[d] = 1;
  return df;
}

// Whether contact i's row depends on the clamped ones': the Schur complement of A_CC in
// A_{C+i, C+i} (the acceleration i would get from a unit force of its own with the clamped
// contacts held) below round-off of A's scale.
bool LcpSolver::dependent(const LcpMatrix& A, int i, double scale_A) const {
  const LcpVector x = on_clamped_set(A, A.col(i));
  return A(i, i) - A.col(i).dot(x) <= 1e-10 * scale_A;
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
  if (!clamped_.empty() && solve_on_clamped_set(As, bs, r)) return r;
  return solve_small(As, bs);
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
  state_.assign(static_cast<std::size_t>(n), kUnset);
  const double scale_A = scale_of(A);
  const double scale_b = scale_of(b);
  const int max_pivots = static_cast<int>(50 * n + 100);  // a guard against cycling
  // Round-off in a = A f + b grows with the forces; "satisfied" and "blocking" are judged against it.
  auto accel_tolerance = [&] { return this->accel_tolerance(scale_A, scale_b, r.f); };

  for (Eigen::Index d = 0; d < n; ++d) {
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
        clamped_.push_back(static_cast<int>(d));
        break;
      }
      if (state_[blocking] == kClamped) {  // its force reached zero: release it
        r.f[blocking] = 0;
        state_[blocking] = kNotClamped;
        clamped_.erase(std::find(clamped_.begin(), clamped_.end(), static_cast<int>(blocking)));
        std::replace(state_.begin(), state_.end(), kDependent, kNotClamped);  // (a smaller set: look again)
      } else {                                                                // its acceleration reached zero: clamp it
        r.a[blocking] = 0;
        state_[blocking] = kClamped;
        clamped_.push_back(static_cast<int>(blocking));
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
