#pragma once
// A JointState's positions for an arm of n joints (n = the arm model's dof()): the components that
// pose an arm from its URDF take the positions only when the message carries exactly n of them,
// and refuse it otherwise with what it carried and what the arm needs.
#include <string>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::msgs {

// Copies m's positions into q (an Eigen vector of dynamic size, resized to n) when m carries n of
// them; else leaves q as it was and says why the message does not fit the arm.
template <class Vector>
std::string joint_positions(const msg::JointState& m, int n, Vector& q) {
  const auto& position = m.position();
  if (static_cast<int>(position.size()) != n)
    return std::to_string(position.size()) + " joint positions, expected " + std::to_string(n) +
           " (the joints of the arm's URDF)";
  q.resize(n);
  for (int j = 0; j < n; ++j) q[j] = position[static_cast<std::size_t>(j)];
  return {};
}

}  // namespace wysiwyf::msgs
