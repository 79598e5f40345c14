// World's contact search at a step's start (world.hpp): the features near enough to look at,
// classified as resting contacts (touching, facing) or watched features (near but apart), and
// the evaluation of one feature's contact point that every phase uses.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

ContactPoint World::point_of(const ContactFeature& f, const std::vector<Pose>& poses) const {
  return evaluate(f, model_.bodies, poses, model_.params.rim_slack);
}

// Two equal boxes face on face meet corner on corner: a corner of each on the other's face, at the
// same point along the same line. The second is the same constraint again (a row of A twice
// over): it only makes the LCP larger.
bool World::twin_of_touching(const ContactFeature& f, const ContactPoint& c) const {
  if (f.kind != ContactKind::kVertexFace) return false;
  const double near = 1e-9 * model_.bodies[f.a].half_extents.maxCoeff();
  // (the candidates come pair by pair: only the last contacts listed can be of f's pair)
  for (auto t = work_.search.touching.rbegin(); t != work_.search.touching.rend(); ++t) {
    const bool same = t->feature.a == f.a && t->feature.b == f.b, swapped = t->feature.a == f.b && t->feature.b == f.a;
    if (!same && !swapped) break;
    if (t->feature.kind != ContactKind::kVertexFace) continue;
    if ((t->point.p - c.p).norm() <= near && t->point.n.dot(c.n) * (same ? 1 : -1) > 1 - 1e-12) return true;
  }
  return false;
}

void World::classify_contacts(double dt) {
  std::vector<Pose>& poses = work_.poses;
  state_.poses_of(model_, state_.bodies, poses);
  work_.search.candidates.clear();
  work_.search.broad_phase.pairs(model_, poses, model_.params.margin, work_.search.pairs);
  const auto sleeps = [&](int i) { return model_.slot[i] < 0 || state_.asleep[i]; };  // (static bodies too)
  for (const auto& [a, b] : work_.search.pairs)
    if (!sleeps(a) || !sleeps(b))
      find_candidates(a, b, model_.bodies, poses, model_.params.margin, model_.params.rim_slack, dt,
                      work_.search.candidates);
  std::vector<ActiveContact>& touching = work_.search.touching;
  std::vector<ContactFeature>& watched = work_.search.watched_next;
  touching.clear();
  watched.clear();
  // Between sleeping bodies nothing has moved: their contacts stay as they were, forces, friction
  // and order included, and so do the features they watch.
  for (const ActiveContact& c : state_.resting)
    if (sleeps(c.feature.a) && sleeps(c.feature.b)) touching.push_back(c);
  for (const ContactFeature& f : state_.watched)
    if (sleeps(f.a) && sleeps(f.b)) watched.push_back(f);
  bool colliding = false;
  // A touching contact still open by g closes under the gap feedback (critically damped at ws)
  // without passing zero if it approaches no faster than ws g: that approach is the feedback's
  // own, not an impact (taken as one, each contact of a pushed pile, made at a few um, would take
  // an impulse at every step while the feedback closes it: an impact a step for seconds).
  const WorldParams& p = model_.params;
  const double closing_allowed = 2 * M_PI * p.stabilisation_hz;
  std::vector<std::uint64_t>& was_resting = work_.search.was_resting;  // (feature keys, sorted)
  was_resting.clear();
  for (const ActiveContact& c : state_.resting) was_resting.push_back(feature_key(c.feature));
  std::sort(was_resting.begin(), was_resting.end());
  for (const auto& f : work_.search.candidates) {
    const ContactPoint c = point_of(f, poses);
    const double gap_allowed = std::binary_search(was_resting.begin(), was_resting.end(), feature_key(f))
                                   ? p.contact_release
                                   : p.contact_tolerance;
    if (!c.valid || c.gap > gap_allowed) {  // apart, or not yet over its face: watched
      watched.push_back(f);
      continue;
    }
    const double opening = c.n.dot(relative_velocity(poses[f.a], poses[f.b], c.p));
    const bool fast = opening < -(p.settle_speed + closing_allowed * std::max(0.0, c.gap));
    if (fast && c.gap > p.contact_tolerance) {  // (held by the hysteresis only: it hits where it touches)
      watched.push_back(f);
      continue;
    }
    if (!separates(f, c, poses, kContactCone)) continue;  // (watched in a wider cone; touching only within)
    if (twin_of_touching(f, c)) continue;
    touching.push_back(ActiveContact{f, c, 0});
    if (fast) colliding = true;
  }
  work_.grouping.group(touching, model_.slot, state_.islands, state_.resting);
  if (colliding) {  // still approaching: an impact at the start of the step
    if (!collide(touching, state_.islands)) ++report_.lcp_failures;
    ++report_.collisions;
    state_.restart = true;
  }
  const bool same_resting =
      touching.size() == state_.resting.size() &&
      std::equal(touching.begin(), touching.end(), state_.resting.begin(),
                 [](const ActiveContact& x, const ActiveContact& y) { return x.feature == y.feature; });
  if (same_resting)  // the same contacts: the friction they held starts this step's solve
    for (std::size_t i = 0; i < touching.size(); ++i) touching[i].friction = state_.resting[i].friction;
  else
    state_.restart = true;
  if (watched != state_.watched) state_.restart = true;
  state_.resting.swap(touching);  // (the scratch vectors keep their capacity)
  state_.watched.swap(watched);
}

}  // namespace wysiwyf::haptics
