#pragma once
// What makes a sample unusable, beside its type: problem(m) says why a sample cannot be used (a
// NaN, an orientation that is no rotation), or returns "" when it can. Component::take_checked
// finds these by the sample's type and rejects what they find; a component with more to check
// (a body its scene has, a source's name) checks that after.
#include <string>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::msgs {

// The largest magnitude any number of a sample may have in SI units (m, rad, m/s, N): nothing a
// lab measures or commands comes near it, and a finite 1e308 overflows to infinity at its first
// square (a distance, a spring's force), so a larger one is refused like a NaN.
constexpr double kMaxMagnitude = 1e4;

// Why a pose cannot be used: a non-finite number, a position beyond kMaxMagnitude, or an
// orientation quaternion far from unit length (a zero quaternion would become a NaN rotation).
// "" when it can.
std::string pose_problem(const geometry_msgs::Pose& p);
// Why a twist cannot be used: a non-finite number or one beyond kMaxMagnitude. "" when it can.
std::string twist_problem(const geometry_msgs::Twist& t);
// Why a sample stamped in another frame than `expected` cannot be used as one in it (a tracker's
// hand in the camera's frame before it knows the camera's pose, read as base). "" when it can.
std::string frame_problem(const std_msgs::Header& h, const char* expected);

}  // namespace wysiwyf::msgs

namespace wysiwyf::msg {

// The pose (pose_problem).
std::string problem(const PoseStamped& m);
// Force and torque finite.
std::string problem(const WrenchStamped& m);
// At least one joint position, all finite; velocities and efforts none or one per joint (a
// velocity or effort may be NaN: unknown).
std::string problem(const JointState& m);
// A tracked hand (not LOST): its position finite. A LOST one carries no position: fine.
std::string problem(const HandPosition& m);
// The pose (pose_problem) and the twist finite.
std::string problem(const CartesianSetpoint& m);
// The body's pose (pose_problem) and twist finite.
std::string problem(const ObjectState& m);
// An attachment: obj_T_dev (pose_problem); a release carries none.
std::string problem(const Attachment& m);

}  // namespace wysiwyf::msg
