// World's impacts (world.hpp, STEP 4-6): the watched gaps after each integrator step, the first
// that closed found at its time of impact, and the impulses of eqs. (15)-(16) over the contacts
// that touch there.
#include <algorithm>
#include <utility>
#include <vector>

#include "rigid_body/contact_system.hpp"
#include "rigid_body/gap_closing.hpp"
#include "rigid_body/ode_integrator.hpp"
#include "rigid_body/state_vector.hpp"
#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

void World::watched_gaps_at(const double* y, std::vector<double>& gaps) {
  std::vector<Pose>& poses = work_.poses;  // (the group's bodies set; its features reach no other dynamic body)
  const std::vector<int>& bodies = *integrated_;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const int i = bodies[k];
    poses[i] = state_.asleep[i] ? state_.static_poses[i] : model_.pose_of(i, unpack_body(y + kStateSize * k));
  }
  gaps.resize(state_.watched.size());
  for (std::size_t k = 0; k < state_.watched.size(); ++k) gaps[k] = watched_gap(point_of(state_.watched[k], poses));
}

double World::watched_gap_at(const ContactFeature& f, const double* y) {
  std::vector<Pose>& poses = work_.impacts.gap_poses;  // (only f's two bodies are set, and read)
  poses.resize(state_.static_poses.size());
  for (const int i : {f.a, f.b}) {
    const int k = groups_.place()[i];  // (in the group's state vector)
    poses[i] = k < 0 || state_.asleep[i] ? state_.static_poses[i] : model_.pose_of(i, unpack_body(y + kStateSize * k));
  }
  return watched_gap(point_of(f, poses));
}

bool World::first_closing(double t_start, double t_reached, std::size_t& feature, double& t_impact) {
  OdeIntegrator& ode = *integrator_;
  std::vector<double>& at_end = work_.impacts.gaps_at_step_end;
  if (state_.watched.empty()) {
    at_end.clear();
    return false;
  }
  watched_gaps_at(ode.state(), at_end);
  const double not_facing = model_.params.margin;  // (watched_gap's value for a feature off its partner)
  bool found = false;
  for (std::size_t k = 0; k < at_end.size(); ++k) {
    double t_lo = t_start, gap_lo = state_.watched_gaps[k], t_hi = t_reached, gap_hi = at_end[k];
    if (!(gap_lo > 0)) continue;  // (approaching only: open at the step's start)
    const ContactFeature& f = state_.watched[k];
    const auto gap_at = [&](double t) { return watched_gap_at(f, ode.state_at(t)); };
    if (!(gap_hi <= 0)) {
      // Facing its partner at the step's start and off it at the end, it may have closed in
      // between and left the face through the other body (a corner of a box tumbling onto
      // another's face within a 1 ms step that nothing else shortened): the step's dense output
      // is looked at within it.
      if (gap_hi != not_facing || gap_lo == not_facing) continue;
      bool closed = false;
      for (int s = 1; s < kLeftFaceSamples && !closed; ++s) {
        const double t = t_start + (t_reached - t_start) * s / kLeftFaceSamples;
        const double g = gap_at(t);
        closed = g <= 0;
        (closed ? t_hi : t_lo) = t;
        (closed ? gap_hi : gap_lo) = g;
      }
      if (!closed) continue;
    }
    const GapClosing c = find_gap_closing(gap_at, t_lo, gap_lo, t_hi, gap_hi, model_.params.impact_tolerance);
    if (!found || c.t < t_impact) t_impact = c.t, feature = k, found = true;
  }
  return found;
}

void World::impact(std::size_t hit) {
  // Every watched feature that touches now takes part, the one that hit or not: the four corners
  // of a cube landing flat hit together, whichever of them closed first.
  std::vector<ActiveContact> contacts = state_.resting;
  std::vector<ContactFeature> still_watched;
  std::vector<double> still_watched_gaps;
  std::vector<Pose> poses;
  state_.poses_of(model_, state_.bodies, poses);
  for (std::size_t k = 0; k < state_.watched.size(); ++k) {
    const ContactPoint c = point_of(state_.watched[k], poses);
    const bool meets = k == hit || (c.valid && c.gap <= model_.params.contact_tolerance);
    if (meets && separates(state_.watched[k], c, poses, kContactCone)) {
      contacts.push_back(ActiveContact{state_.watched[k], c, 0});
    } else {
      still_watched.push_back(state_.watched[k]);
      still_watched_gaps.push_back(watched_gap(c));  // (the impulses move no body: the gaps stay)
    }
  }
  work_.grouping.group(contacts, model_.slot, state_.islands, state_.resting);  // (they rest from here on)
  if (!collide(contacts, state_.islands)) ++report_.lcp_failures;
  ++report_.collisions;
  ++group_collisions_;
  state_.resting = std::move(contacts);
  settle_islands(false);  // an island the impact joined to a sleeping one wakes it (the caller restarts)
  state_.watched = std::move(still_watched);
  state_.watched_gaps = std::move(still_watched_gaps);
  if (group_collisions_ >= model_.params.max_collisions_per_step) {  // no more events this step
    state_.watched.clear();
    state_.watched_gaps.clear();
  }
}

bool World::collide(std::vector<ActiveContact>& contacts, const std::vector<ContactIsland>& islands) {
  if (contacts.empty()) return true;
  std::vector<Pose>& poses = work_.impacts.impact_poses;
  state_.poses_of(model_, state_.bodies, poses);
  for (auto& c : contacts) c.point = point_of(c.feature, poses);
  bool ok = true;
  for (const ContactIsland& island : islands)
    ok = collide_island(contacts.data() + island.begin, island.end - island.begin, poses) && ok;
  return ok;
}

bool World::collide_island(const ActiveContact* contacts, std::size_t count, const std::vector<Pose>& poses) {
  // An island where nothing approaches takes no impulse (the LCP's answer is zero): not solved.
  bool approaching = false;
  for (std::size_t i = 0; i < count && !approaching; ++i) {
    const ActiveContact& contact = contacts[i];
    approaching =
        contact.point.n.dot(relative_velocity(poses[contact.feature.a], poses[contact.feature.b], contact.point.p)) < 0;
  }
  if (!approaching) return true;
  ContactSystem& cs = contact_system_;
  const bool friction = cs.friction_coefficients(contacts, count);
  cs.build(contacts, count, poses, friction);
  const auto m = static_cast<Eigen::Index>(count);
  Eigen::VectorXd c(m), ct(friction ? 2 * m : 0);
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& contact = contacts[static_cast<std::size_t>(i)];
    const Vec3 v = relative_velocity(poses[contact.feature.a], poses[contact.feature.b], contact.point.p);
    const double v_rel = contact.point.n.dot(v);
    double e = std::min(model_.bodies[contact.feature.a].restitution, model_.bodies[contact.feature.b].restitution);
    if (v_rel > -model_.params.resting_speed) e = 0;  // a slow approach ends the bounce sequence
    c[i] = (1 + e) * v_rel;                           // eq. (14): v+ + e v- >= 0
    if (friction)  // target: no tangential velocity after the impact (within mu times the normal impulse)
      for (int k = 0; k < 2; ++k)
        ct[2 * i + k] = cs.tangents[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].dot(v);
  }
  Eigen::VectorXd jn, jt;
  if (friction) {
    const FrictionResult r = impact_friction_.solve(lcp_, cs.A, c, ct, cs.mu, ct);
    if (!r.ok) return false;
    if (!r.converged) ++report_.friction_unconverged;
    jn = r.fn, jt = r.ft;
  } else {
    const LcpResult r = lcp_.solve(cs.A, c);
    if (!r.ok) return false;
    jn = r.f;
  }
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& contact = contacts[static_cast<std::size_t>(i)];
    Vec3 j = jn[i] * contact.point.n;
    if (friction) {
      const auto& t = cs.tangents[static_cast<std::size_t>(i)];
      j += jt[2 * i] * t[0] + jt[2 * i + 1] * t[1];
    }
    apply_impulse(contact, j, poses);
  }
  return !friction || stop_approach(contacts, count);
}

// Friction's staggered rounds can end (unsettled, or settled on a bounded cone) with a contact
// still approaching: a tipping cube's far corners, swung down by the friction at the near ones.
// The resting LCP that follows only keeps accelerations from closing, so such a contact would sink
// at its speed for the whole step. A frictionless, fully inelastic impact over the same contacts
// takes that speed away; it never changes a contact that already separates, so after a good
// impact it does nothing.
bool World::stop_approach(const ActiveContact* contacts, std::size_t count) {
  std::vector<Pose>& poses = work_.impacts.after_impact_poses;
  state_.poses_of(model_, state_.bodies, poses);
  const auto m = static_cast<Eigen::Index>(count);
  Eigen::VectorXd c(m);
  double fastest = 0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& contact = contacts[static_cast<std::size_t>(i)];
    c[i] = contact.point.n.dot(relative_velocity(poses[contact.feature.a], poses[contact.feature.b], contact.point.p));
    fastest = std::min(fastest, c[i]);
  }
  if (fastest >= -kStillApproaching) return true;
  contact_system_.build(contacts, count, poses, false);
  const LcpResult r = lcp_.solve(contact_system_.A, c);
  if (!r.ok) return false;
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& contact = contacts[static_cast<std::size_t>(i)];
    apply_impulse(contact, Vec3(r.f[i] * contact.point.n), poses);
  }
  return true;
}

void World::apply_impulse(const ActiveContact& contact, const Vec3& j, const std::vector<Pose>& poses) {
  apply_at_contact(contact.feature, contact.point.p, j, model_.slot, poses,
                   [&](int, int body, const Vec3& on_body, const Vec3& moment) {
                     state_.bodies[body].P += on_body;
                     state_.bodies[body].L += moment;
                   });
}

}  // namespace wysiwyf::haptics
