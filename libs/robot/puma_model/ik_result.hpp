#pragma once
// Results of the closed-form inverse kinematics: no exceptions for poses the arm cannot take.
#include <array>

#include "puma_model/types.hpp"

namespace wysiwyf::robot {

enum class IkStatus {
  kOk,
  kInvalidInput,            // a non-finite pose or joint vector
  kOutOfReach,              // the wrist centre is farther than the stretched arm, or nearer
                            // than the folded arm, from the shoulder
  kInsideShoulderCylinder,  // the wrist centre is nearer to the joint-1 axis than the shoulder
                            // offset (d2 + d3)
  kJointLimits,             // reachable, but every solution violates a joint limit
};

const char* to_string(IkStatus status);

// One of the eight PUMA solutions. Index bits: 1 = left arm, 2 = second elbow root,
// 4 = wrist flipped. Angles are wrapped by 2 pi into the joint limits where that is possible
// (choosing the representative nearest the reference configuration), else into (-pi, pi].
struct IkSolution {
  Vector6d q = Vector6d::Zero();
  bool valid = false;           // the position is reachable on this shoulder/elbow branch
  bool within_limits = false;   // valid and every joint inside its limits
  bool left_arm = false;        // wrist centre behind the shoulder (Paul's "lefty")
  bool elbow_up = false;        // elbow above the shoulder-to-wrist line
  bool wrist_flip = false;      // theta5 <= 0 branch
  bool wrist_singular = false;  // theta5 ~ 0: theta4 was kept at the reference value
};

struct IkSolutions {
  std::array<IkSolution, 8> solution{};
  // kOk: at least one solution within limits; kJointLimits: valid ones, none within limits;
  // else why the pose is unreachable (or the input invalid).
  IkStatus status = IkStatus::kInvalidInput;
  int valid_count = 0;
  int within_limits_count = 0;
};

struct IkResult {
  IkStatus status = IkStatus::kInvalidInput;
  Vector6d q = Vector6d::Zero();  // the chosen solution when status == kOk
  int solution_index = -1;
  bool wrist_singular = false;

  bool ok() const { return status == IkStatus::kOk; }
};

}  // namespace wysiwyf::robot
