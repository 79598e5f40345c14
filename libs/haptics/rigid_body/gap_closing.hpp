#pragma once
// Where within an integrator step a watched gap closes: the time of impact of section 4.3's
// STEP 4. The integrator's dense output gives the state anywhere in its last step; this finds,
// by the Illinois variant of regula falsi, a time where the gap is within a physical tolerance
// of zero, evaluating that one gap only. (SUNDIALS' own root finding evaluates every watched
// gap at each of its iterations and narrows the time to a hundred round-offs: in a pushed pile,
// a hundred gaps watched, a fifth of a slow step's time.)
#include <cmath>
#include <limits>

namespace wysiwyf::haptics {

struct GapClosing {
  double t = 0;    // where the gap was found closed (within the tolerance) or the step's end
  double gap = 0;  // the gap there
  int evaluations = 0;
};

// gap(t) over [t_lo, t_hi], open at t_lo (gap_lo > 0), closed at t_hi (gap_hi <= 0): returns the
// first point found with |gap| <= gap_tolerance or, where the gap jumps (a feature that starts
// to face its partner when already through it), the closed end once the two ends are within
// SUNDIALS' time tolerance (100 round-offs of t and of the step).
template <class Gap>
GapClosing find_gap_closing(Gap&& gap, double t_lo, double gap_lo, double t_hi, double gap_hi, double gap_tolerance) {
  const double time_tolerance = 100 * std::numeric_limits<double>::epsilon() * (std::abs(t_hi) + std::abs(t_hi - t_lo));
  GapClosing found{t_hi, gap_hi, 0};
  if (gap_hi >= -gap_tolerance) return found;
  double weight_lo = gap_lo, weight_hi = gap_hi;  // (Illinois: an end kept twice has its weight halved)
  int kept = 0;                                   // +1: the open end was kept last, -1: the closed one
  while (t_hi - t_lo > time_tolerance) {
    double t = t_hi - weight_hi * (t_hi - t_lo) / (weight_hi - weight_lo);
    // (a secant point at an end, or past it, makes no progress: bisect instead)
    if (!(t > t_lo + 0.5 * time_tolerance && t < t_hi - 0.5 * time_tolerance)) t = 0.5 * (t_lo + t_hi);
    const double g = gap(t);
    ++found.evaluations;
    if (std::abs(g) <= gap_tolerance) return GapClosing{t, g, found.evaluations};
    if (g > 0) {
      t_lo = t, weight_lo = g;
      if (kept == -1) weight_hi *= 0.5;
      kept = -1;
    } else {
      t_hi = t, weight_hi = g, gap_hi = g;
      if (kept == 1) weight_lo *= 0.5;
      kept = 1;
    }
  }
  return GapClosing{t_hi, gap_hi, found.evaluations};
}

}  // namespace wysiwyf::haptics
