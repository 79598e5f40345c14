// The vector operations installed over SUNDIALS' (fast_serial_ops.hpp) give SUNDIALS' own results,
// aliased arguments included, to round-off.
#include <nvector/nvector_serial.h>

#include <array>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "rigid_body/fast_serial_ops.hpp"

namespace wysiwyf::haptics {
namespace {

constexpr sunindextype kLength = 13 * 17 + 1;  // a 17-box pile's state, and one over

class FastSerialOps : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(SUNContext_Create(nullptr, &ctx_), 0);
    for (std::size_t k = 0; k < theirs_.size(); ++k) {
      theirs_[k] = N_VNew_Serial(kLength, ctx_);
      ours_[k] = N_VNew_Serial(kLength, ctx_);
      install_fast_serial_ops(ours_[k]);
    }
    ASSERT_NE(ours_[0]->ops->nvlinearsum, theirs_[0]->ops->nvlinearsum) << "not installed";
    fill(7);
  }
  // The same random numbers in ours and theirs.
  void fill(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-2, 2);
    for (std::size_t k = 0; k < theirs_.size(); ++k)
      for (sunindextype i = 0; i < kLength; ++i) NV_Ith_S(ours_[k], i) = NV_Ith_S(theirs_[k], i) = u(rng);
  }
  void TearDown() override {
    for (auto* v : theirs_) N_VDestroy(v);
    for (auto* v : ours_) N_VDestroy(v);
    SUNContext_Free(&ctx_);
  }
  // The largest difference between our vector k and theirs, relative to its largest element.
  double apart(std::size_t k) const {
    double diff = 0, scale = 0;
    for (sunindextype i = 0; i < kLength; ++i) {
      diff = std::max(diff, std::abs(NV_Ith_S(ours_[k], i) - NV_Ith_S(theirs_[k], i)));
      scale = std::max(scale, std::abs(NV_Ith_S(theirs_[k], i)));
    }
    return diff / scale;
  }

  SUNContext ctx_ = nullptr;
  std::array<N_Vector, 6> theirs_{}, ours_{};
};

TEST_F(FastSerialOps, LinearSumScaleAndConstantAsSundials) {
  N_VLinearSum(0.3, ours_[0], -1.7, ours_[1], ours_[2]);
  N_VLinearSum_Serial(0.3, theirs_[0], -1.7, theirs_[1], theirs_[2]);
  N_VLinearSum(2.0, ours_[3], 0.5, ours_[4], ours_[3]);  // z = x
  N_VLinearSum_Serial(2.0, theirs_[3], 0.5, theirs_[4], theirs_[3]);
  N_VScale(-0.25, ours_[5], ours_[5]);
  N_VScale_Serial(-0.25, theirs_[5], theirs_[5]);
  for (std::size_t k : {2, 3, 5}) EXPECT_LE(apart(k), 1e-15) << k;
  N_VConst(0.125, ours_[1]);
  N_VConst_Serial(0.125, theirs_[1]);
  EXPECT_EQ(apart(1), 0.0);
}

TEST_F(FastSerialOps, WeightedRmsNormAsSundials) {
  EXPECT_NEAR(N_VWrmsNorm(ours_[0], ours_[1]), N_VWrmsNorm_Serial(theirs_[0], theirs_[1]),
              1e-15 * N_VWrmsNorm_Serial(theirs_[0], theirs_[1]));
}

TEST_F(FastSerialOps, LinearCombinationOfOneToFiveVectorsAsSundialsIntoTheFirstToo) {
  std::array<sunrealtype, 5> c = {0.5, -1.25, 2.0, 0.75, -0.1};
  for (int count = 1; count <= 5; ++count) {
    for (const bool into_first : {false, true}) {
      fill(static_cast<unsigned>(count));
      std::array<N_Vector, 5> x_ours{}, x_theirs{};
      for (int j = 0; j < 5; ++j) x_ours[j] = ours_[j], x_theirs[j] = theirs_[j];
      N_Vector z_ours = into_first ? ours_[0] : ours_[5], z_theirs = into_first ? theirs_[0] : theirs_[5];
      ASSERT_EQ(N_VLinearCombination(count, c.data(), x_ours.data(), z_ours), 0);
      ASSERT_EQ(N_VLinearCombination_Serial(count, c.data(), x_theirs.data(), z_theirs), 0);
      EXPECT_LE(apart(into_first ? 0 : 5), 1e-15) << count << " vectors" << (into_first ? ", into the first" : "");
    }
  }
}

}  // namespace
}  // namespace wysiwyf::haptics
