// The least-norm least-squares solve of the friction rounds (psd_pseudo_inverse.hpp) against
// Eigen's complete orthogonal decomposition, on random symmetric positive semi-definite systems
// of the friction solve's shapes and ranks: J M^-1 J^T-like, k rows from fewer free motions
// (both answers carry round-off of about epsilon times the condition, up to 1e8 here).
#include <random>

#include <gtest/gtest.h>

#include "rigid_body/psd_pseudo_inverse.hpp"

namespace wysiwyf::haptics {
namespace {

TEST(PsdPseudoInverse, MatchesTheCompleteOrthogonalDecompositionOnRankDeficientSystems) {
  std::mt19937 rng(7), columns_rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> size(1, 60);
  PsdPseudoInverse inverse;
  Eigen::VectorXd x;
  Eigen::MatrixXd X, Z;
  double worst = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const int k = size(rng), r = std::uniform_int_distribution<int>(0, k)(rng);
    // B = G D G^T of rank r, its free motions' scales spread over three decades (a light box on
    // a heavy one); the right-hand sides have parts outside B's range (least squares).
    Eigen::MatrixXd G(k, r);
    for (Eigen::Index i = 0; i < G.size(); ++i) G.data()[i] = u(rng);
    Eigen::VectorXd scale(r);
    for (int j = 0; j < r; ++j) scale[j] = std::pow(10.0, 1.5 * (u(rng) + 1));
    const Eigen::MatrixXd B = G * scale.asDiagonal() * G.transpose();
    // 3 to 12 columns (half_solve takes many another way), the first 3 drawn as before.
    Eigen::MatrixXd C(k, 3 + trial % 10);
    for (Eigen::Index i = 0; i < 3 * k; ++i) C.data()[i] = u(rng);
    for (Eigen::Index i = 3 * k; i < C.size(); ++i) C.data()[i] = u(columns_rng);
    inverse.compute(B, 1e-12);
    ASSERT_EQ(inverse.rank(), r) << "k " << k;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-10);
    cod.compute(B);
    const Eigen::MatrixXd expected = cod.solve(C);
    const double size_of = std::max(1.0, expected.cwiseAbs().maxCoeff());
    inverse.solve(C, X);
    worst = std::max(worst, (X - expected).cwiseAbs().maxCoeff() / size_of);
    EXPECT_LT((X - expected).cwiseAbs().maxCoeff(), 1e-7 * size_of) << "k " << k << " rank " << r;
    inverse.solve(C.col(1), x);
    EXPECT_LT((x - expected.col(1)).cwiseAbs().maxCoeff(), 1e-7 * size_of);
    x = C.col(2);
    inverse.solve(x, x);  // in place
    EXPECT_LT((x - expected.col(2)).cwiseAbs().maxCoeff(), 1e-7 * size_of);
    if (r > 0) {
      inverse.half_solve(C, Z);  // C^T B^+ C = Z^T Z
      const Eigen::MatrixXd sandwich = C.transpose() * expected;
      EXPECT_LT((Z.transpose() * Z - sandwich).cwiseAbs().maxCoeff(),
                1e-7 * std::max(1.0, sandwich.cwiseAbs().maxCoeff()));
    }
  }
  std::printf("[measured] worst difference from the COD, relative to the solution: %.3g\n", worst);
}

TEST(PsdPseudoInverse, AFacesFourCornersShareALoadEvenly) {
  // Four coplanar corners under one body (rank 3): the least-norm forces for the body's weight
  // through its centre are equal.
  Eigen::MatrixXd J(4, 3);  // rows: the corners' normal rows over (z, roll, pitch)
  J << 1, 0.1, 0.1, 1, -0.1, 0.1, 1, -0.1, -0.1, 1, 0.1, -0.1;
  const Eigen::MatrixXd B = J * J.transpose();
  PsdPseudoInverse inverse;
  inverse.compute(B, 1e-12);
  EXPECT_EQ(inverse.rank(), 3);
  Eigen::VectorXd f_vertex(4), f;
  f_vertex << 5.0, 0.0, 5.0, 0.0;  // a vertex of the LCP: two opposite corners carry it
  const Eigen::VectorXd same_motion = B * f_vertex;
  inverse.solve(same_motion, f);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(f[i], 2.5, 1e-12) << "corner " << i;
}

}  // namespace
}  // namespace wysiwyf::haptics
