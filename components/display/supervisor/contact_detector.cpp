#include "contact_detector.hpp"

namespace wysiwyf::display {

ContactDetector::Event ContactDetector::update(std::int64_t now_ns, double force, double hand_distance, bool in_contact,
                                               double hand_sigma) {
  const auto held = [&](std::int64_t& since, bool condition, double dwell) {
    if (!condition) {
      since = -1;
      return false;
    }
    if (since < 0) since = now_ns;
    return static_cast<double>(now_ns - since) * 1e-9 >= dwell;
  };
  const bool hand_known = hand_distance >= 0;
  if (!in_contact) {
    below_since_ = -1;
    if (!held(above_since_, force > t_.contact_force, t_.contact_dwell)) return Event::kNone;
    above_since_ = -1;
    return !hand_known || hand_distance <= t_.contact_distance + 3 * hand_sigma ? Event::kTouch : Event::kForeignForce;
  }
  above_since_ = -1;
  if (!held(below_since_, force < t_.release_force, t_.release_dwell)) return Event::kNone;
  if (hand_known && hand_distance < t_.release_distance) return Event::kNone;  // resting on it still
  below_since_ = -1;
  return Event::kRelease;
}

}  // namespace wysiwyf::display
