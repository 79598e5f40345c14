#pragma once
// Results and settings of ArmModel's inverse kinematics, for any number of joints: every
// solution found, the nearest one within limits, or why none. No exceptions for poses the arm
// cannot take.
#include <array>

#include "arm_model/arm_types.hpp"

namespace wysiwyf::robot {

// How an ArmModel solves IK, chosen at load time from the chain's geometry.
enum class ArmIkMethod {
  kPumaClosedForm,  // PUMA 560 geometry in DH layout: PumaModel's closed form, 8 solutions
  kUrClosedForm,    // UR-type 6R (three parallel middle axes, UR DH twists): closed form, 8 solutions
  kNumerical,       // damped least squares from several seeds, joint limits, null space to q_ref
};

// A readable name of the method.
const char* to_string(ArmIkMethod method);

enum class ArmIkStatus {
  kOk,            // at least one solution within limits
  kInvalidInput,  // a non-finite pose or joint vector
  kOutOfReach,    // closed form: no branch reaches the pose
  kJointLimits,   // closed form: reachable, but every solution violates a joint limit
  kNotFound,      // numerical: no seed converged (out of reach, or a pose the seeds missed)
};

// A readable reason for the status.
const char* to_string(ArmIkStatus status);

// The most solutions one ik() call returns (8 for the closed forms).
constexpr int kMaxIkSolutions = 16;

struct ArmIkSolution {
  JointVector q;               // angles wrapped by 2 pi to the representative nearest q_ref
  bool within_limits = false;  // every joint inside its limits
  bool singular = false;       // closed form at a wrist singularity: one angle kept at q_ref
  int branch = -1;             // closed form: the branch index (0..7); numerical: the seed index
};

struct ArmIkSolutions {
  std::array<ArmIkSolution, kMaxIkSolutions> solution{};
  int count = 0;                // solutions [0, count) are valid (reach the pose)
  int within_limits_count = 0;  // of those, inside the joint limits
  ArmIkStatus status = ArmIkStatus::kInvalidInput;
  ArmIkMethod method = ArmIkMethod::kNumerical;
};

struct ArmIkResult {
  ArmIkStatus status = ArmIkStatus::kInvalidInput;
  JointVector q;  // the chosen solution when ok()
  int branch = -1;
  bool singular = false;

  // Whether q holds a solution.
  bool ok() const { return status == ArmIkStatus::kOk; }
};

// Settings of the numerical IK (the closed forms use none of them).
struct ArmIkOptions {
  int seeds = 24;                // spread seeds used after q_ref (deterministic, within limits)
  int max_iterations = 150;      // per seed
  double tolerance = 1e-10;      // position [m] and rotation [rad] error at which a seed converged
  double null_tolerance = 1e-8;  // redundant arms: null-space step [rad] at which q_ref is reached
  double null_gain = 1.0;        // redundant arms: fraction of the null-space part of (q_ref - q)
                                 // applied per step (halved while a step does not bring q nearer)
  double max_step = 0.5;         // largest joint change per iteration [rad or m]
  double duplicate = 1e-4;       // solutions closer than this (max over joints) are one
  double local_radius = 0.25;    // ik_nearest returns the q_current seed's solution at once when
                                 // it lies this close to q_current (Euclidean, joint space)
  double limit_margin = 0.3;     // redundant arms: the null-space goal keeps this far [rad or m]
                                 // inside every position limit (at most a quarter of its range), so
                                 // the self-motion turns a joint away from a limit the path nears
  double limit_push = 0.01;      // redundant arms: the most one call moves the goal from q_ref
                                 // towards that inner range [rad or m] (a gentle drift, not a jump)
};

}  // namespace wysiwyf::robot
