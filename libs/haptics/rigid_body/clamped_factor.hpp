#pragma once
// The Cholesky factor L (A_CC = L L^T) of the clamped contacts' block of the LCP matrix, kept up
// to date as the pivoting clamps and releases contacts: a contact clamped appends a row from the
// forward solve its direction needed anyway, one released is taken out by Givens rotations. Each
// costs O(|C|^2) where factorising A_CC anew at every pivot would cost O(|C|^3) (Baraff 1994, section 6,
// keeps his factorisation incremental for the same reason). The pivoting keeps C non-singular, so
// the factor exists; an append whose pivot round-off has eaten reports it, and the caller
// factorises afresh.
#include "rigid_body/lcp_types.hpp"

namespace wysiwyf::haptics {

class ClampedFactor {
 public:
  ClampedFactor() : L_(kMaxLcpSize, kMaxLcpSize) {}
  void clear() { n_ = 0; }
  int size() const { return n_; }

  // y = L^-1 v (v over C, in C's order): half a solve, and what clamping contact i needs with
  // v = A(C, i).
  void forward(LcpVector& v) const;
  // x = L^-T y: the other half.
  void back(LcpVector& y) const;
  // x = A_CC^-1 v, in place.
  void solve(LcpVector& v) const {
    forward(v);
    back(v);
  }
  // Clamps one more contact whose row of A over C is v: l = L^-1 v (forward) and its own
  // diagonal entry A_ii. False, leaving the factor as it was, where the new pivot
  // A_ii - l.l is not above `floor` (the row depends on the clamped ones').
  bool append(const LcpVector& l, double a_ii, double floor);
  // Releases the k-th clamped contact (in C's order).
  void remove(int k);

 private:
  LcpMatrix L_;  // the leading n_ x n_ block; its strict upper triangle is kept zero
  int n_ = 0;
};

}  // namespace wysiwyf::haptics
