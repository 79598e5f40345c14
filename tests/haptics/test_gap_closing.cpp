// The time of impact inside an integrator step (gap_closing.hpp): found where the gap is within the
// tolerance of zero, in a few evaluations of that one gap, and where a gap jumps through zero (a
// corner that starts to face its partner already past it), at the jump.
#include <cmath>

#include <gtest/gtest.h>

#include "rigid_body/gap_closing.hpp"

namespace wysiwyf::haptics {
namespace {

TEST(GapClosing, AFallingCornerIsFoundWithinTheToleranceInAFewEvaluations) {
  // A corner 1 mm above a face, closing at 0.3 m/s under gravity: it meets it at t*.
  const double g0 = 1e-3, v = 0.3, a = 9.81;
  const auto gap = [&](double t) { return g0 - v * t - 0.5 * a * t * t; };
  const double t_star = (-v + std::sqrt(v * v + 2 * a * g0)) / a;
  const double t_lo = 0.0, t_hi = 0.004;  // one integrator step past it
  const GapClosing c = find_gap_closing(gap, t_lo, gap(t_lo), t_hi, gap(t_hi), 1e-10);
  EXPECT_LE(std::abs(c.gap), 1e-10);
  EXPECT_NEAR(c.gap, gap(c.t), 0.0);
  EXPECT_NEAR(c.t, t_star, 1e-10 / v);
  EXPECT_LE(c.evaluations, 6) << "Illinois converges superlinearly";
}

TEST(GapClosing, AGapThatClosesAtTheStepsEndNeedsNoSearch) {
  const auto gap = [](double) -> double {
    ADD_FAILURE() << "evaluated";
    return 0;
  };
  const GapClosing c = find_gap_closing(gap, 0.0, 1e-4, 1e-3, -5e-11, 1e-10);
  EXPECT_EQ(c.t, 1e-3);
  EXPECT_EQ(c.evaluations, 0);
}

TEST(GapClosing, AGapThatJumpsThroughZeroIsFoundAtTheJump) {
  // Not facing (the margin, 1 cm) until t = 0.3 ms, then 2 mm deep: no point within the tolerance.
  const double jump = 3e-4;
  const auto gap = [&](double t) { return t < jump ? 0.01 : -0.002; };
  const GapClosing c = find_gap_closing(gap, 0.0, 0.01, 1e-3, -0.002, 1e-10);
  EXPECT_GE(c.t, jump);
  EXPECT_LE(c.t - jump, 1e-15);
  EXPECT_EQ(c.gap, -0.002);
  EXPECT_LT(c.evaluations, 100);
}

}  // namespace
}  // namespace wysiwyf::haptics
