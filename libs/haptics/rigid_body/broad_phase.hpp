#pragma once
// The broad phase of contact search: which pairs of bodies can touch at all, before their
// corners and edges are looked at (contact.hpp's find_candidates). Sweep and prune (Baraff's
// thesis, 1992, section 6.3): each body's world-axis bounding box, grown by the margin; the boxes
// sorted by their lower end along the axis the bodies spread most; a sweep keeps the boxes whose
// interval is still open and tests each new one against those alone. The order is kept between
// calls, so the sort is an insertion sort over a list that is almost sorted already.
#include <utility>
#include <vector>

#include "rigid_body/contact.hpp"
#include "rigid_body/world_model.hpp"

namespace wysiwyf::haptics {

using BodyPair = std::pair<int, int>;  // (a, b): a dynamic; b static, or dynamic and above a

struct BodyExtent {  // a world-axis bounding box
  Vec3 lo, hi;
};

class SweepAndPrune {
 public:
  // The pairs whose grown boxes overlap, in (a, b) order: the order the contacts are listed in.
  void pairs(const WorldModel& model, const std::vector<Pose>& poses, double margin, std::vector<BodyPair>& out);

 private:
  std::vector<BodyExtent> boxes_;
  std::vector<int> order_;  // bodies by their box's lower end along axis_
  std::vector<int> open_;   // the sweep's boxes whose interval has not closed
  int axis_ = 0;
};

// The same pairs by testing every pair's boxes: the reference the sweep is checked and measured
// against.
void all_pairs(const WorldModel& model, const std::vector<Pose>& poses, double margin, std::vector<BodyPair>& out);

}  // namespace wysiwyf::haptics
