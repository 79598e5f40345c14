#pragma once
// The linear complementarity problem of the paper's eqs. (9)-(10) and (15)-(16):
//   find f >= 0 with a = A f + b >= 0 and f . a = 0,
// for a symmetric positive semi-definite A (contact space inverse inertia). Solved by Baraff's
// pivoting method ("Fast contact force computation for nonpenetrating rigid bodies", SIGGRAPH
// 1994, section 5): contacts are driven to complementarity one at a time, keeping the clamped
// set C (f > 0, a = 0) and the not-clamped set NC (f = 0, a > 0) consistent. Redundant contacts
// (four coplanar corners of a resting cube) would make A_CC singular: a contact whose row depends
// on the clamped ones' is kept out of C, so A_CC stays positive definite and its Cholesky factor
// is kept up to date pivot by pivot (clamped_factor.hpp); where round-off defeats that, A_CC is
// factorised afresh for each solve, with a rank-revealing decomposition as the last resort.
#include <Eigen/Dense>

#include <algorithm>
#include <vector>

#include "rigid_body/clamped_factor.hpp"
#include "rigid_body/lcp_types.hpp"

namespace wysiwyf::haptics {

struct LcpResult {
  LcpVector f;         // the forces (or impulses), >= 0
  LcpVector a;         // A f + b, >= 0
  LcpIndices clamped;  // the final clamped set C: a warm start for a nearby problem
  int pivots = 0;
  bool warm = false;  // solved on the warm start's clamped set, without pivoting
  bool ok = false;    // false: no solution within the pivot limit (A not PSD, or degenerate cycling)
  // The natural complementarity residual max_i |min(f_i, a_i)|: 0 exactly at a solution.
  double residual() const;
};

class LcpSolver {
 public:
  // tolerance: how negative a_i may be and still count as satisfied (scaled by max |A|, |b|).
  explicit LcpSolver(double tolerance = 1e-12) : tol_(tolerance) {}
  LcpResult solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);
  // Warm start: the clamped set of a nearby problem (the previous right-hand side's, the previous
  // friction round's). If the forces that hold exactly those contacts at zero acceleration are a
  // solution (f_C >= 0, a elsewhere >= 0), they are returned without pivoting; otherwise the
  // pivoting method goes on from the part of the set that still holds. Either way the result is
  // an exact solution.
  LcpResult solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const LcpIndices& warm_start);

 private:
  // Throws std::length_error beyond kMaxLcpSize contacts.
  LcpResult solve_small(const LcpMatrix& A, const LcpVector& b);
  // Baraff's drive-to-zero of every contact still unset in state_, from r's forces, which keep
  // the others complementary (clamped: f >= 0 at a = 0; not clamped: f = 0, a >= 0).
  LcpResult drive(const LcpMatrix& A, const LcpVector& b, LcpResult& r);
  // From a warm start that is no solution: its clamped set less the contacts it would pull
  // (negative forces), the rest marked satisfied or unset. False where its factor failed.
  bool start_from_clamped_set(const LcpMatrix& A, const LcpVector& b, LcpResult& r);
  // The solution with clamped set C (clamped_), if there is one.
  bool solve_on_clamped_set(const LcpMatrix& A, const LcpVector& b, LcpResult& r);
  LcpVector on_clamped_set(const LcpMatrix& A, const LcpVector& rhs) const;
  bool dependent(const LcpMatrix& A, int i, double scale_A);
  // L^-1 A(C, i) from the factor, remembered for clamping i while C stays as it is.
  const LcpVector& forward_column(const LcpMatrix& A, int i);
  // Adds i to C (and to the factor, or gives the factor up where it cannot take i).
  void clamp(const LcpMatrix& A, int i, double scale_A);
  // Takes i out of C (and out of the factor).
  void release(int i);
  // The factor of the whole clamped set (a warm start's, or one grown out of the small sets).
  void factorise(const LcpMatrix& A, double scale_A);
  // Whether the kept factor is A_CC's (else A_CC is factorised afresh for each solve).
  bool factored() const;
  // How negative an acceleration may be and still count as satisfied: round-off in a = A f + b
  // grows with the forces.
  double accel_tolerance(double scale_A, double scale_b, const LcpVector& f) const {
    return tol_ * std::max({1.0, scale_b, scale_A * f.cwiseAbs().maxCoeff()});
  }
  LcpVector direction(const LcpMatrix& A, int d);
  void polish(const LcpMatrix& A, const LcpVector& b, LcpResult& r);

  double tol_;
  std::vector<int> clamped_;    // C, in insertion order
  std::vector<char> state_;     // per contact: 0 unset, 1 clamped, 2 not clamped
  ClampedFactor factor_;        // of A_CC, in C's order, while factored()
  bool factor_failed_ = false;  // round-off defeated it in this solve
  int column_of_ = -1;          // the contact whose L^-1 A(C, i) column_ holds (-1: none, or C changed since)
  LcpVector column_;
};

}  // namespace wysiwyf::haptics
