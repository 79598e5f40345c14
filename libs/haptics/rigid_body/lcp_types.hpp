#pragma once
// The LCP's vectors and matrices: Eigen's dynamic sizes with a fixed capacity, so a solve works on
// the stack with no heap allocation.
#include <Eigen/Dense>

namespace wysiwyf::haptics {

// Up to this many contacts the solver works on the stack: no heap allocation per solve.
constexpr int kMaxLcpSize = 96;
using LcpVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLcpSize, 1>;
using LcpMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLcpSize, kMaxLcpSize>;
using LcpIndices = Eigen::Matrix<int, Eigen::Dynamic, 1, 0, kMaxLcpSize, 1>;

}  // namespace wysiwyf::haptics
