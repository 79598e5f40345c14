#pragma once
// Contacts: for every touch or miss the (simulated) user reports, whether it was a hit, how long
// the plate had been still before the finger arrived, and how far the plate was from the pose that
// displays the feature at that moment (mm, deg; the nearest of the plate's four turns about the
// face normal, since the square plate shows the face in each).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "pose_history.hpp"
#include "scene/scene.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::display {

class ContactOutcomes {
 public:
  // still_speed: m/s, the plate slower than this counts as still.
  explicit ContactOutcomes(double still_speed = 0.002) : still_speed_(still_speed) {}

  // The report of a USER_TOUCH or USER_MISS event stamped t (kept for the summary).
  const msg::ContactReport& measure(const msg::UserEvent& event, std::int64_t t, const haptics::Scene& scene,
                                    const PoseHistory& poses);
  // The log line of one report.
  static std::string line(const msg::ContactReport& r);
  // "<n> contact(s), <m> hit(s)".
  std::string tally() const;
  // The summary's "contacts" member.
  void write_json(std::ostream& j) const;

 private:
  // Walking back from t, the last 100 ms window the plate moved in (over a shorter one the
  // encoders' quantisation, 0.06 mm a step, reads as motion): when it has been still since.
  std::int64_t still_since(const PoseTrack& plate, std::int64_t t) const;

  double still_speed_;
  std::vector<msg::ContactReport> reports_;
};

}  // namespace wysiwyf::display
