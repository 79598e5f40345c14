#pragma once
// The linear complementarity problem of the paper's eqs. (9)-(10) and (15)-(16):
//   find f >= 0 with a = A f + b >= 0 and f . a = 0,
// for a symmetric positive semi-definite A (contact space inverse inertia). Solved by Baraff's
// pivoting method ("Fast contact force computation for nonpenetrating rigid bodies", SIGGRAPH
// 1994, section 5): contacts are driven to complementarity one at a time, keeping the clamped
// set C (f > 0, a = 0) and the not-clamped set NC (f = 0, a > 0) consistent. Redundant contacts
// (four coplanar corners of a resting cube) make A_CC singular; the direction solve uses a
// rank-revealing decomposition, which Baraff shows always has a solution in the frictionless case.
#include <Eigen/Dense>

#include <algorithm>
#include <vector>

namespace wysiwyf::haptics {

// Up to this many contacts the solver works on the stack: no heap allocation per solve.
constexpr int kMaxLcpSize = 96;
using LcpVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLcpSize, 1>;
using LcpMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLcpSize, kMaxLcpSize>;
using LcpIndices = Eigen::Matrix<int, Eigen::Dynamic, 1, 0, kMaxLcpSize, 1>;

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
  // pivoting method runs as without it. Either way the result is an exact solution.
  LcpResult solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const LcpIndices& warm_start);

 private:
  // Throws std::length_error beyond kMaxLcpSize contacts.
  LcpResult solve_small(const LcpMatrix& A, const LcpVector& b);
  // The solution with clamped set C (clamped_), if there is one.
  bool solve_on_clamped_set(const LcpMatrix& A, const LcpVector& b, LcpResult& r);
  LcpVector on_clamped_set(const LcpMatrix& A, const LcpVector& rhs) const;
  bool dependent(const LcpMatrix& A, int i, double scale_A) const;
  // How negative an acceleration may be and still count as satisfied: round-off in a = A f + b
  // grows with the forces.
  double accel_tolerance(double scale_A, double scale_b, const LcpVector& f) const {
    return tol_ * std::max({1.0, scale_b, scale_A * f.cwiseAbs().maxCoeff()});
  }
  LcpVector direction(const LcpMatrix& A, int d);
  void polish(const LcpMatrix& A, const LcpVector& b, LcpResult& r);

  double tol_;
  std::vector<int> clamped_;  // C, in insertion order
  std::vector<char> state_;   // per contact: 0 unset, 1 clamped, 2 not clamped
};

}  // namespace wysiwyf::haptics
