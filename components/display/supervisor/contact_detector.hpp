#pragma once
// When the user touches the plate and when they let go, from the wrist sensor (the user's force:
// the reading less the tool's weight) held over a dwell time, with the tracked hand as a cross-
// check: a touch needs the hand near the plate, a release needs it leaving (or not tracked).
#include <cstdint>

namespace wysiwyf::display {

struct ContactThresholds {
  double contact_force = 2.0;      // N
  double contact_dwell = 0.02;     // s the force stays above contact_force
  double release_force = 1.0;      // N
  double release_dwell = 0.1;      // s the force stays below release_force
  double contact_distance = 0.05;  // m: a touch needs a tracked hand this near the plate
  double release_distance = 0.02;  // m: a release needs a tracked hand at least this far from it
};

class ContactDetector {
 public:
  enum class Event { kNone, kTouch, kRelease, kForeignForce };

  explicit ContactDetector(ContactThresholds t = {}) : t_(t) {}

  // One force sample (N, the user's) at now_ns; hand_distance < 0: no hand tracked; hand_sigma:
  // the tracker's standard deviation (m, its covariance's largest axis). `in_contact`: the
  // display's current view. A touch needs the hand within contact_distance + 3 sigma (a tracker
  // that says it is unsure may be that far off); kForeignForce: a force held on the plate while
  // even that cannot explain it (something else touches the arm). A release needs the best
  // estimate of the hand at least release_distance away.
  Event update(std::int64_t now_ns, double force, double hand_distance, bool in_contact, double hand_sigma = 0);
  void reset() { above_since_ = below_since_ = -1; }

 private:
  ContactThresholds t_;
  std::int64_t above_since_ = -1, below_since_ = -1;
};

}  // namespace wysiwyf::display
