#pragma once
// The scripted user's actions, in terms of the virtual scene (a parameter: one action a line):
//
//   reach FEATURE [at U V] [speed V]   reach for a feature ("cube +x knob", "cube +z face at 0.02 -0.03"),
//                                      minimum-jerk, peak speed V m/s (default 1.0; people reach at up to 1.6)
//   push F T                           press on the touched surface with F newtons, for T s (0.3 s ramp)
//   drag DX DY DZ T                    move the pressing finger by (DX, DY, DZ) m in the base frame, over T s
//   release T                          let the force go to nothing over T s
//   withdraw D T                       pull the hand back D m along the surface's normal, over T s
//   move X Y Z T                       move the hand to (X, Y, Z) m in the base frame, over T s
//   wait T                             keep still for T s
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace wysiwyf::display {

struct UserAction {
  enum class Kind { kReach, kPush, kDrag, kRelease, kWithdraw, kMove, kWait } kind = Kind::kWait;
  const haptics::DisplayFeature* feature = nullptr;  // reach
  double u = 0, v = 0;                               // reach: where on a face feature, m from its touch centre
  double speed = 1.0;                                // reach: peak speed, m/s
  double force = 0;                                  // push
  Eigen::Vector3d vector = Eigen::Vector3d::Zero();  // drag: displacement; move: the point
  double distance = 0;                               // withdraw
  double duration = 0;                               // s (reach: from the distance and the speed)
};

// Parses the script against the scene's features; throws std::invalid_argument naming the line
// (1-based) and what was expected.
std::vector<UserAction> parse_user_script(const std::vector<std::string>& lines, const haptics::Scene& scene);

}  // namespace wysiwyf::display
