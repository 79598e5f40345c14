// Baraff's pivoting LCP on random and degenerate contact problems.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "rigid_body/clamped_factor.hpp"
#include "rigid_body/lcp.hpp"

namespace wysiwyf::haptics {

// A contact problem as physics poses it: `contacts` contacts at random points of three mutually
// adjacent faces of `bodies` 20 cm boxes (each box sits in a corner of floor and walls, or of
// other boxes), each pushing into its face, so
// A = J M^-1 J^T is symmetric positive semi-definite and singular as soon as contacts outnumber
// 6 * bodies or several lie on one face; b = J M^-1 F for a random applied wrench F. (An
// arbitrary b outside the range of J can make an LCP infeasible; a physical one cannot.)
struct Problem {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
};

Problem contact_problem(std::mt19937& rng, int contacts, int bodies) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(contacts, 6 * bodies);
  Eigen::MatrixXd Minv = Eigen::MatrixXd::Zero(6 * bodies, 6 * bodies);
  for (int k = 0; k < bodies; ++k) {
    const double mass = 0.2 + 2 * std::abs(u(rng));
    Minv.block<3, 3>(6 * k, 6 * k) = Eigen::Matrix3d::Identity() / mass;
    Minv.block<3, 3>(6 * k + 3, 6 * k + 3) = Eigen::Matrix3d::Identity() / (mass * 0.04 / 6);
  }
  std::vector<std::array<int, 3>> corner(bodies);  // per body: which side of each axis is held
  for (auto& c : corner)
    for (int axis = 0; axis < 3; ++axis) c[axis] = 2 * axis + std::uniform_int_distribution<int>(0, 1)(rng);
  for (int i = 0; i < contacts; ++i) {
    const int body = std::uniform_int_distribution<int>(0, bodies - 1)(rng);
    const int face = corner[body][std::uniform_int_distribution<int>(0, 2)(rng)];
    Eigen::Vector3d outward = Eigen::Vector3d::Zero();
    outward[face / 2] = face % 2 ? 1 : -1;
    Eigen::Vector3d r(0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng));
    r[face / 2] = 0.1 * outward[face / 2];
    const Eigen::Vector3d n = -outward;  // from the surroundings into the box
    J.block<1, 3>(i, 6 * body) = n.transpose();
    J.block<1, 3>(i, 6 * body + 3) = r.cross(n).transpose();
  }
  Eigen::VectorXd F(6 * bodies);
  for (Eigen::Index i = 0; i < F.size(); ++i) F[i] = 10 * u(rng);
  return Problem{J * Minv * J.transpose(), J * Minv * F};
}

// The four bottom corners of a resting cube (plus a duplicate corner): rank 3 for 4 or 5 contacts.
Eigen::MatrixXd resting_cube_matrix(bool duplicate) {
  const double m = 1.0, h = 0.1;
  const Eigen::Matrix3d Iinv = Eigen::Matrix3d::Identity() / (m * (2 * h) * (2 * h) / 6);
  std::vector<Eigen::Vector3d> corners = {{-h, -h, -h}, {h, -h, -h}, {-h, h, -h}, {h, h, -h}};
  if (duplicate) corners.push_back({h, h, -h});
  Eigen::MatrixXd J(corners.size(), 6);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
    J.block<1, 3>(i, 0) = n.transpose();
    J.block<1, 3>(i, 3) = corners[i].cross(n).transpose();
  }
  Eigen::MatrixXd Minv = Eigen::MatrixXd::Zero(6, 6);
  Minv.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / m;
  Minv.bottomRightCorner<3, 3>() = Iinv;
  return J * Minv * J.transpose();
}

// A problem solved, then its loads moved (each by `by` times a draw from [-1, 1]) and solved
// again, from nothing and from the first answer's clamped set (a warm start).
struct NearbySolves {
  LcpResult first, cold, warm;
  Eigen::VectorXd b;  // the moved loads
};
NearbySolves solve_nearby(LcpSolver& solver, const Problem& p, double by, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  NearbySolves s;
  s.first = solver.solve(p.A, p.b);
  s.b = p.b;
  for (Eigen::Index i = 0; i < s.b.size(); ++i) s.b[i] += by * u(rng);
  s.cold = solver.solve(p.A, s.b);
  s.warm = solver.solve(p.A, s.b, s.first.clamped);
  return s;
}

TEST(Lcp, SolvesTenThousandRandomAndDegenerateProblemsToComplementarity) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  LcpSolver solver;
  double worst = 0;
  int failures = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    Problem p;
    switch (trial % 4) {
      case 0: p = contact_problem(rng, 1 + trial % 12, 3); break;  // mostly regular
      case 1: p = contact_problem(rng, 8 + trial % 9, 1); break;   // more contacts than DOF: singular
      case 2: {  // coplanar, redundant, under gravity and a random push
        p.A = resting_cube_matrix(trial % 8 == 2);
        const Eigen::Vector3d push(u(rng), u(rng), 5 * u(rng));
        p.b = Eigen::VectorXd::Constant(p.A.rows(), -9.81 + push.z());
        break;
      }
      default: p = contact_problem(rng, 1 + trial % 24, 2); break;
    }
    const Eigen::MatrixXd& A = p.A;
    const Eigen::VectorXd& b = p.b;
    const LcpResult r = solver.solve(A, b);
    if (!r.ok) {
      ++failures;
      if (failures <= 8)
        ADD_FAILURE() << "trial " << trial << " (kind " << trial % 4 << ", " << b.size()
                      << " contacts): no solution after " << r.pivots << " pivots, min a " << r.a.minCoeff()
                      << ", max f " << r.f.maxCoeff();
      continue;
    }
    EXPECT_LE((A * r.f + b - r.a).cwiseAbs().maxCoeff(), 1e-9);
    if (r.residual() > 1e-9 && failures < 8) {
      ++failures;
      ADD_FAILURE() << "trial " << trial << " (kind " << trial % 4 << ", " << b.size() << " contacts): residual "
                    << r.residual() << " after " << r.pivots << " pivots, max f " << r.f.maxCoeff();
    }
    worst = std::max(worst, r.residual());
  }
  EXPECT_EQ(failures, 0);
  EXPECT_LE(worst, 1e-9);
}

TEST(Lcp, ACubeRestingOnFourCornersCarriesItsWeight) {
  const Eigen::MatrixXd A = resting_cube_matrix(false);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(4, -9.81);  // gravity pulls every corner down
  const LcpResult r = LcpSolver().solve(A, b);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.f.sum(), 9.81, 1e-9);  // m g, shared among the corners
  EXPECT_LE(r.a.cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Lcp, SeparatingContactsGetNoForce) {
  const Eigen::MatrixXd A = resting_cube_matrix(false);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(4, 2.0);
  const LcpResult r = LcpSolver().solve(A, b);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.f.cwiseAbs().maxCoeff(), 0.0);
}

// A warm start from the clamped set of a nearby problem (the previous right-hand side's) is
// taken when it is a solution and skips the pivoting; a stale or malformed one is never trusted.
TEST(Lcp, WarmStartFromANearbyProblemSolvesWithoutPivotingAndNeverTrustsABadSet) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  LcpSolver solver;
  int warm = 0, trials = 0;
  double worst = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Problem p = trial % 2 ? contact_problem(rng, 1 + trial % 12, 2) : Problem{resting_cube_matrix(trial % 4 == 0), {}};
    if (trial % 2 == 0) p.b = Eigen::VectorXd::Constant(p.A.rows(), -9.81 + u(rng));
    // The next right-hand side: the same contacts, slightly different loads.
    const NearbySolves next = solve_nearby(solver, p, 1e-3, rng);
    ASSERT_TRUE(next.first.ok);
    const Eigen::VectorXd& b2 = next.b;
    const LcpResult &cold = next.cold, &r = next.warm;
    ASSERT_TRUE(r.ok);
    ++trials;
    if (r.warm) {
      ++warm;
      EXPECT_EQ(r.pivots, 0);
    }
    worst = std::max(worst, r.residual());
    EXPECT_LE((p.A * r.f + b2 - r.a).cwiseAbs().maxCoeff(), 1e-9);
    // The accelerations of a frictionless LCP are unique, whichever forces produce them.
    EXPECT_LE((r.a - cold.a).cwiseAbs().maxCoeff(), 1e-9) << "trial " << trial;
  }
  EXPECT_LE(worst, 1e-9);
  EXPECT_GT(warm, trials / 2);  // nearby problems mostly keep their clamped set

  // A set that is no solution (a lifted corner clamped), indices out of range, duplicates:
  // the pivoting method answers.
  const Eigen::MatrixXd A = resting_cube_matrix(false);
  Eigen::VectorXd b = Eigen::VectorXd::Constant(4, -9.81);
  b[3] = 50;  // corner 3 is pulled away hard
  for (const LcpIndices& bad : {LcpIndices{{0, 1, 3}}, LcpIndices{{0, 7}}, LcpIndices{{1, 1}}, LcpIndices{{-1}}}) {
    const LcpResult r = solver.solve(A, b, bad);
    ASSERT_TRUE(r.ok);
    EXPECT_FALSE(r.warm);
    EXPECT_LE(r.residual(), 1e-9);
    EXPECT_EQ(r.f[3], 0.0);
  }
}

// A warm start that is no longer a solution (the loads changed enough to open or close contacts)
// still starts the pivoting: from its clamped set less the contacts it would pull, to the same
// exact accelerations as from nothing, in far fewer pivots (a pushed pile's 28 contacts: 5-9
// pivots where from nothing 62-76).
TEST(Lcp, AWarmStartThatNoLongerHoldsGoesOnPivotingFromWhatStillHolds) {
  std::mt19937 rng(11);
  LcpSolver solver;
  long warm_pivots = 0, cold_pivots = 0;
  int pivoted = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Problem p = contact_problem(rng, 16 + trial % 13, 4);  // 16-28 contacts, singular from 25
    const NearbySolves next = solve_nearby(solver, p, 0.3 * p.b.cwiseAbs().maxCoeff(), rng);
    ASSERT_TRUE(next.first.ok);
    const Eigen::VectorXd& b2 = next.b;
    const LcpResult &cold = next.cold, &r = next.warm;
    ASSERT_TRUE(r.ok) << "trial " << trial;
    EXPECT_LE(r.residual(), 1e-9) << "trial " << trial;
    EXPECT_LE((p.A * r.f + b2 - r.a).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LE((r.a - cold.a).cwiseAbs().maxCoeff(), 1e-8 * std::max(1.0, b2.cwiseAbs().maxCoeff()))
        << "trial " << trial;
    if (r.warm) continue;
    ++pivoted;
    warm_pivots += r.pivots, cold_pivots += cold.pivots;
  }
  EXPECT_GT(pivoted, 500);  // most of these warm starts no longer hold
  EXPECT_LT(warm_pivots, cold_pivots / 2) << warm_pivots << " pivots from the warm starts, " << cold_pivots << " cold";
}

// The incrementally kept factor solves A_CC x = v as a fresh factorisation of the same set does,
// through a random sequence of 2000 contacts clamped and released (at any position), and refuses
// a contact whose row is a combination of the clamped ones'.
TEST(ClampedFactor, ClampingAndReleasingInAnyOrderSolvesAsAFreshFactorisation) {
  std::mt19937 rng(7);
  const Problem p = contact_problem(rng, 60, 8);  // 60 contacts on 8 bodies: rank 48 at most
  const LcpMatrix A = p.A;
  const double scale = A.cwiseAbs().maxCoeff();
  ClampedFactor factor;
  std::vector<int> set;
  double worst = 0;
  int refused = 0;
  for (int op = 0; op < 2000; ++op) {
    const bool add = set.empty() || (set.size() < 40 && std::uniform_int_distribution<int>(0, 2)(rng) > 0);
    if (add) {
      const int i = std::uniform_int_distribution<int>(0, 59)(rng);
      if (std::find(set.begin(), set.end(), i) != set.end()) continue;
      LcpVector l(static_cast<Eigen::Index>(set.size()));
      for (std::size_t k = 0; k < set.size(); ++k) l[static_cast<Eigen::Index>(k)] = A(set[k], i);
      factor.forward(l);
      if (!factor.append(l, A(i, i), 1e-10 * scale)) {
        ++refused;
        continue;
      }
      set.push_back(i);
    } else {
      const int k = std::uniform_int_distribution<int>(0, static_cast<int>(set.size()) - 1)(rng);
      factor.remove(k);
      set.erase(set.begin() + k);
    }
    ASSERT_EQ(factor.size(), static_cast<int>(set.size()));
    const auto n = static_cast<Eigen::Index>(set.size());
    Eigen::MatrixXd Acc(n, n);
    for (Eigen::Index r = 0; r < n; ++r)
      for (Eigen::Index c = 0; c < n; ++c) Acc(r, c) = A(set[r], set[c]);
    const Eigen::VectorXd v = Eigen::VectorXd::Random(n);
    LcpVector x = v;
    factor.solve(x);
    // The residual of the system, against A_CC's scale: what a solve can promise.
    worst = std::max(
        worst, (Acc * Eigen::VectorXd(x) - v).cwiseAbs().maxCoeff() / std::max(1.0, scale * x.cwiseAbs().maxCoeff()));
  }
  std::printf("clamped factor: worst relative residual %.3g over 2000 operations, %d dependent contacts refused\n",
              worst, refused);
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(refused, 0) << "60 contacts of rank 48: some rows must depend on the others";
}

}  // namespace wysiwyf::haptics
