#include "rigid_body/world.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "rigid_body/contact_system.hpp"
#include "rigid_body/arkode_integrator.hpp"
#include "rigid_body/cvode_integrator.hpp"
#include "rigid_body/gap_closing.hpp"
#include "rigid_body/state_vector.hpp"

namespace wysiwyf::haptics {

namespace {

// (checked ahead of the model's own checks: a count mismatch is the error reported first)
std::vector<BodyModel> one_state_each(std::vector<BodyModel>& models, const std::vector<BodyState>& initial) {
  if (models.size() != initial.size()) throw std::invalid_argument("World: one initial state per body expected");
  return std::move(models);
}

}  // namespace

World::World(std::vector<BodyModel> models, std::vector<BodyState> initial, WorldParams params)
    : model_(one_state_each(models, initial), params), state_(model_, std::move(initial)), contact_system_(model_) {
  impact_friction_.stick_first = false;
  integrated_ = &model_.dynamic;
  // (every body's entry, so that a group's right-hand side sets only its own bodies')
  work_.states = state_.bodies;
  work_.poses = state_.static_poses;
}

std::unique_ptr<OdeIntegrator> World::make_integrator(int bodies) {
  const WorldParams& p = model_.params;
  const IntegratorOptions options{
      p.rtol, p.atol, p.initial_step, p.restart_growth, p.nonlinear_convergence, p.max_integrator_steps};
  const int size = kStateSize * std::max(1, bodies);
  if (p.integrator == Integrator::kAdams) return std::make_unique<CvodeIntegrator>(size, options, *this);
  return std::make_unique<ArkodeIntegrator>(size, options, *this);
}

World::~World() = default;

void World::set_external_wrench(int body, const Vec3& force, const Vec3& torque) {
  state_.set_wrench(body, force, torque);
}
ContactPoint World::point_of(const ContactFeature& f, const std::vector<Pose>& poses) const {
  return evaluate(f, model_.bodies, poses, model_.params.rim_slack);
}

void World::apply_impulse(const ActiveContact& contact, const Vec3& j, const std::vector<Pose>& poses) {
  apply_at_contact(contact.feature, contact.point.p, j, model_.slot, poses,
                   [&](int, int body, const Vec3& on_body, const Vec3& moment) {
                     state_.bodies[body].P += on_body;
                     state_.bodies[body].L += moment;
                   });
}

void World::set_state(int i, const BodyState& s) { state_.set_body(model_, i, s); }

void World::copy_state_from(const World& other) {
  if (other.body_count() != body_count() || other.model_.dynamic != model_.dynamic)
    throw std::invalid_argument("World::copy_state_from: the other world has other bodies");
  state_ = other.state_;
  state_.restart = true;  // (this world's integrators have not seen that state)
}

bool World::watching(int i) const {
  return std::any_of(state_.watched.begin(), state_.watched.end(),
                     [i](const ContactFeature& f) { return f.a == i || f.b == i; });
}
double World::energy() const { return state_.energy(model_); }

std::size_t World::evaluate_resting(const std::vector<Pose>& poses, bool within_step) {
  std::vector<ActiveContact>& resting = state_.resting;
  std::size_t total = 0;
  for (ContactIsland& island : state_.islands) {
    if (island.asleep) {  // (nothing of it moves: its points stay as they were)
      total += island.live;
      continue;
    }
    std::size_t live = island.begin;
    for (std::size_t i = island.begin; i < island.end; ++i) {
      ContactPoint& point = resting[i].point;
      point = point_of(resting[i].feature, poses);
      // Every resting contact faced its feature when the step began. Dropped where a trial stage
      // finds it a hair past the rim, it would come back at the next: its force would switch on
      // and off between the integrator's stages, a discontinuity that fails the error test until
      // the step has shrunk (a pushed pile's haptic step would take dozens of integrator steps).
      // Within the step it keeps its force while within the margin; the next step's
      // classification drops it (supported at most one step, 1 ms, past the rim).
      if (!point.valid && within_step) {
        point = evaluate(resting[i].feature, model_.bodies, poses, model_.params.margin);
      }
      if (point.valid) std::swap(resting[i], resting[live++]);
    }
    island.live = live - island.begin;
    total += island.live;
  }
  return total;
}

void World::update_friction(double dt) {
  ContactSystem& cs = contact_system_;
  std::vector<ActiveContact>& resting = state_.resting;
  // (without friction coefficients no contact ever carries friction: nothing to do)
  if (!cs.friction_coefficients(resting.data(), resting.size())) return;
  std::vector<Pose>& poses = work_.poses;
  state_.poses_of(model_, state_.bodies, poses);
  const std::size_t live = evaluate_resting(poses, false);
  if (live > 0) {
    cs.applied_loads(state_, model_.dynamic, poses, false);
    cs.accelerations(model_.dynamic, state_.bodies, poses);
  }
  bool any = false;
  for (const ContactIsland& island : state_.islands) {
    if (island.asleep) continue;  // (at rest: its friction stays as it was)
    ActiveContact* active = resting.data() + island.begin;
    const std::size_t n = island.live;
    const bool friction = n > 0 && cs.friction_coefficients(active, n);
    if (friction) {
      cs.build(active, n, poses, true);
      cs.free_terms(active, n, poses, dt);
      // The last step's friction (classify_contacts carries it over while the contacts stay the
      // same), in the tangent bases, starts the rounds.
      work_.ft_start.resize(static_cast<Eigen::Index>(2 * n));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < 2; ++j)
          work_.ft_start[static_cast<Eigen::Index>(2 * i + j)] = cs.tangents[i][j].dot(active[i].friction);
    }
    // (before solving: no failed solve leaves it applied)
    for (std::size_t i = island.begin; i < island.end; ++i) resting[i].friction.setZero();
    if (!friction) continue;
    FrictionResult r = friction_.solve(lcp_, cs.A, cs.b, cs.bt, cs.mu, cs.vt, work_.ft_start, island.clamped);
    if (!r.ok) r = friction_.solve(lcp_, cs.A, cs.b_free, cs.bt, cs.mu, cs.vt);
    report_.friction_rounds += r.iterations;
    if (!r.ok) continue;  // frictionless this step; the normal LCP of the right-hand side reports it
    if (!r.converged) ++report_.friction_unconverged;
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      active[i].friction = r.ft[2 * k] * cs.tangents[i][0] + r.ft[2 * k + 1] * cs.tangents[i][1];
    }
    any = true;
  }
  // A new friction load: a discontinuity of the right-hand side, like a new wrench.
  if (any) state_.restart = true;
}

void World::rhs(const double* y, double* ydot) {
  ++report_.rhs_evaluations;
  ContactSystem& cs = contact_system_;
  std::vector<ActiveContact>& resting = state_.resting;
  std::vector<BodyState>& states = work_.states;
  std::vector<Pose>& poses = work_.poses;
  // The group's bodies at y; a sleeping one's pose is the one kept when it fell asleep. (Its
  // contacts reach no other dynamic body, and the static bodies' poses are always set.)
  const std::vector<int>& bodies = *integrated_;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const int i = bodies[k];
    states[i] = unpack_body(y + kStateSize * k);
    poses[i] = state_.asleep[i] ? state_.static_poses[i] : model_.pose_of(i, states[i]);
  }
  // Resting contacts at this very state.
  const std::size_t live = evaluate_resting(poses, true);
  // Gravity, the user's wrench and the friction held for this step, then, island by island, the
  // normal forces of eqs. (9)-(10) that keep the contacts from closing under them.
  cs.applied_loads(state_, bodies, poses, true);
  std::vector<Vec3>& force = cs.force;
  std::vector<Vec3>& torque = cs.torque;
  if (live > 0) cs.accelerations(bodies, states, poses);
  for (ContactIsland& island : state_.islands) {
    if (island.asleep) continue;  // (its forces stay as they were)
    ActiveContact* active = resting.data() + island.begin;
    for (std::size_t i = island.live; i < island.end - island.begin; ++i) active[i].force = 0;
    if (island.live == 0) continue;
    cs.build(active, island.live, poses);
    cs.free_terms(active, island.live, poses, 0);
    // Warm-started from the last right-hand side's clamped set: the contacts rarely change
    // between evaluations, and then one small solve replaces the pivoting.
    LcpResult r = lcp_.solve(cs.A, cs.b, island.clamped);
    // The gap feedback is not a physical acceleration: with redundant contacts whose gaps disagree
    // (a cube in the corner of a table and a wall) it can ask for the impossible. The physical
    // problem is always solvable (frictionless, b in the range of J): fall back to it.
    if (!r.ok) r = lcp_.solve(cs.A, cs.b_free);
    if (!r.ok) {  // (its forces are where the pivoting stopped: never applied)
      ++report_.lcp_failures;
      throw RetryWithSmallerStep("the contact LCP of an island of " + std::to_string(island.live) +
                                 " contacts has no solution found");
    }
    island.clamped = r.clamped;
    for (std::size_t i = 0; i < island.live; ++i) {
      const double f = r.f[static_cast<Eigen::Index>(i)];
      active[i].force = f;
      const auto& c = active[i].point;
      apply_at_contact(active[i].feature, c.p, Vec3(f * c.n), model_.slot, poses,
                       [&](int, int body, const Vec3& fn, const Vec3& moment) {
                         force[body] += fn;
                         torque[body] += moment;
                       });
    }
  }
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const int i = bodies[k];
    if (state_.asleep[i]) {  // at rest: its state stays
      std::fill_n(ydot + kStateSize * k, kStateSize, 0.0);
      continue;
    }
    const Pose& p = poses[i];
    write_derivative(p.v, p.omega, states[i].q, force[i], torque[i], ydot + kStateSize * k);
  }
}

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
  std::vector<Pose>& poses = work_.gap_poses;  // (only f's two bodies are set, and read)
  poses.resize(state_.static_poses.size());
  for (const int i : {f.a, f.b}) {
    const int k = groups_.place()[i];  // (in the group's state vector)
    poses[i] = k < 0 || state_.asleep[i] ? state_.static_poses[i] : model_.pose_of(i, unpack_body(y + kStateSize * k));
  }
  return watched_gap(point_of(f, poses));
}

bool World::collide(std::vector<ActiveContact>& contacts, const std::vector<ContactIsland>& islands) {
  if (contacts.empty()) return true;
  std::vector<Pose>& poses = work_.impact_poses;
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
  std::vector<Pose>& poses = work_.after_impact_poses;
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

// Two equal boxes face on face meet corner on corner: a corner of each on the other's face, at the
// same point along the same line. The second is the same constraint again (a row of A twice
// over): it only makes the LCP larger.
bool World::twin_of_touching(const ContactFeature& f, const ContactPoint& c) const {
  if (f.kind != ContactKind::kVertexFace) return false;
  const double near = 1e-9 * model_.bodies[f.a].half_extents.maxCoeff();
  // (the candidates come pair by pair: only the last contacts listed can be of f's pair)
  for (auto t = work_.touching.rbegin(); t != work_.touching.rend(); ++t) {
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
  work_.candidates.clear();
  work_.broad_phase.pairs(model_, poses, model_.params.margin, work_.pairs);
  const auto sleeps = [&](int i) { return model_.slot[i] < 0 || state_.asleep[i]; };  // (static bodies too)
  for (const auto& [a, b] : work_.pairs)
    if (!sleeps(a) || !sleeps(b))
      find_candidates(a, b, model_.bodies, poses, model_.params.margin, model_.params.rim_slack, dt, work_.candidates);
  std::vector<ActiveContact>& touching = work_.touching;
  std::vector<ContactFeature>& watched = work_.watched_next;
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
  std::vector<std::uint64_t>& was_resting = work_.was_resting;  // (feature keys, sorted)
  was_resting.clear();
  for (const ActiveContact& c : state_.resting) was_resting.push_back(feature_key(c.feature));
  std::sort(was_resting.begin(), was_resting.end());
  for (const auto& f : work_.candidates) {
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

StepReport World::step(double dt) {
  report_ = StepReport{};
  if (model_.dynamic.empty()) {
    state_.t += dt;
    return report_;
  }
  const double t_start = state_.t;
  work_.step_start = state_.bodies;
  try {
    integrate(dt, true);
  } catch (const std::exception& e) {
    last_failure_ = e.what();
    // Held friction is a load the normal forces do not see change within the step; where it made
    // the step fail, the step is taken again from its start without it.
    ++report_.frictionless_retries;
    restart_from(t_start, work_.step_start);
    try {
      integrate(dt, false);
    } catch (const std::exception& e) {
      hold(t_start + dt, e.what());
    }
  }
  report_.bodies_asleep = static_cast<int>(std::count(state_.asleep.begin(), state_.asleep.end(), 1));
  return report_;
}

void World::restart_from(double t, const std::vector<BodyState>& bodies) {
  integrated_ = &model_.dynamic;  // (a failure may come from within a group)
  state_.bodies = bodies;
  state_.t = t;
  state_.resting.clear();
  state_.islands.clear();
  state_.watched.clear();
  state_.watched_gaps.clear();
  state_.restart = true;
  state_.wake_all();  // (the contacts are found again from nothing: the sleeping ones' too)
}

// The bodies go back to where the step began and stop there: no motion comes from a step that
// could not be integrated, and a robot following an object stays where it is. The contacts are
// found again from there.
void World::hold(double t, const std::string& why) {
  restart_from(t, work_.step_start);
  for (const int i : model_.dynamic) state_.bodies[i].P.setZero(), state_.bodies[i].L.setZero();
  ++report_.integration_failures;
  last_failure_ = why;
}

void World::integrate(double dt, bool friction) {
  classify_contacts(dt);
  if (settle_islands(false)) state_.restart = true;  // (pushed, hit, or joined to an awake body: awake)
  if (all_asleep()) {                                // nothing moves (the integrator starts over when something wakes)
    state_.t += dt;
    return;
  }
  if (friction) update_friction(dt);
  // The groups are formed again wherever the integration starts over (new contacts, new watched
  // features, a body woken or fallen asleep: every change of the links that join them).
  const bool restart = state_.restart;
  if (restart) {
    groups_.form(model_, state_, [this](int bodies) { return make_integrator(bodies); });
    // The error test is an RMS over the state vector: over a group's bodies alone it is stricter
    // than over the whole world's state by sqrt(world / group). Scaled so that it stays the
    // world's (a body alone in motion among sleeping ones is held to the world's tolerance, not a
    // tighter one): unscaled, a pushed pile's jammed group would spend more right-hand sides a
    // step, each an LCP of its contacts, on accuracy the tolerance does not ask for.
    const double world = static_cast<double>(model_.dynamic.size());
    for (std::size_t k = 0; k < groups_.size(); ++k) {
      IntegrationGroup& g = groups_.groups()[k];
      const double loosen = std::sqrt(world / static_cast<double>(g.bodies.size()));
      g.integrator->set_tolerances(model_.params.rtol * loosen, model_.params.atol * loosen);
    }
  }
  groups_.assign(model_, state_);
  const double t_start = state_.t, t_end = t_start + dt;
  std::vector<IntegrationGroup>& groups = groups_.groups();
  std::size_t awake = 0;
  for (std::size_t k = 0; k < groups_.size(); ++k) awake += groups[k].awake;
  // One group with everything: integrated in place (a cube, a stack, a pile that is one island).
  const bool shared_out = awake > 1 || !groups_.asleep_islands().empty() || !groups_.asleep_watched().empty();
  if (shared_out) {
    work_.all_resting.swap(state_.resting);
    work_.all_islands.swap(state_.islands);
    work_.all_watched.swap(state_.watched);
    work_.all_gaps.swap(state_.watched_gaps);
    work_.all_gaps.resize(work_.all_watched.size());  // (stale where restarting: found again)
    work_.watched_gone.assign(work_.all_watched.size(), 0);
    work_.island_replaced.assign(work_.all_islands.size(), 0);
    work_.joined_resting.clear();
    work_.joined_islands.clear();
  }
  bool any_impacted = false;
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    const IntegrationGroup& g = groups[k];
    if (!g.awake) continue;
    if (shared_out) take_share(g, restart);
    state_.t = t_start;
    integrated_ = &g.bodies;
    integrator_ = g.integrator.get();
    const int collisions = report_.collisions;
    integrate_group(t_end, restart);
    const bool impacted = report_.collisions > collisions;
    any_impacted = any_impacted || impacted;
    if (shared_out) give_back(g, impacted);
  }
  integrated_ = &model_.dynamic;
  if (shared_out) gather_groups(any_impacted);
  state_.t = t_end;
  state_.restart = false;
  // (at the step's end, where the last right-hand side left every contact's force: a sleeping
  // island keeps them)
  if (settle_islands(true)) state_.restart = true;
}

void World::integrate_group(double t_end, bool restart) {
  OdeIntegrator& ode = *integrator_;
  const std::vector<int>& bodies = *integrated_;
  double* y = ode.state();
  group_collisions_ = 0;
  if (restart) {
    for (const int i : bodies) state_.bodies[i].q.normalize();
    pack_state(state_.bodies, bodies, y);
    ode.restart(state_.t);
    watched_gaps_at(y, state_.watched_gaps);
  }
  ode.set_stop_time(t_end);
  while (state_.t < t_end) {
    const double t_start = state_.t;
    double t_reached = t_start;
    ode.take_step(t_end, t_reached);
    ode.count_work(report_.integrator_steps, report_.error_test_failures);
    std::size_t hit = 0;
    double t_impact = t_reached;
    if (first_closing(t_start, t_reached, hit, t_impact)) {
      // The bodies where it hit; the integrator starts over from there after the impulses.
      std::copy_n(ode.state_at(t_impact), kStateSize * bodies.size(), y);
      unpack_state(y, bodies, state_.bodies);
      state_.t = t_impact;
      impact(hit);
      pack_state(state_.bodies, bodies, y);
      ode.restart(state_.t);
      ode.set_stop_time(t_end);  // (a restart clears it)
      continue;
    }
    unpack_state(y, bodies, state_.bodies);
    state_.t = t_reached;
    state_.watched_gaps.swap(work_.gaps_at_step_end);
  }
}

bool World::first_closing(double t_start, double t_reached, std::size_t& feature, double& t_impact) {
  OdeIntegrator& ode = *integrator_;
  std::vector<double>& at_end = work_.gaps_at_step_end;
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

bool World::settle_islands(bool may_sleep) {
  const WorldParams& p = model_.params;
  if (p.sleep_after <= 0) return false;
  const double t = state_.t;
  const std::vector<int>& dynamic = *integrated_;  // (within a group's integration, its bodies only)
  for (const int i : dynamic) {  // who moves now: the fastest point of each body, and the user's wrenches
    const bool pushed = !state_.ext_force[i].isZero() || !state_.ext_torque[i].isZero();
    if (pushed) {
      state_.still_since[i] = t;
      continue;
    }
    if (state_.asleep[i] && state_.bodies[i].P.isZero(0) && state_.bodies[i].L.isZero(0)) continue;  // (not hit)
    const BodyKinematics k(model_.bodies[i], state_.bodies[i], model_.inv_inertia_body[i]);
    if (k.v.norm() + k.omega.norm() * model_.bodies[i].half_extents.norm() > p.sleep_speed) state_.still_since[i] = t;
  }
  bool changed = false;
  std::vector<char>& in_island = work_.in_island;
  in_island.assign(model_.bodies.size(), 0);
  std::vector<int>& bodies = work_.island_bodies;
  for (ContactIsland& island : state_.islands) {
    bodies.clear();
    for (std::size_t c = island.begin; c < island.end; ++c)
      for (const int i : {state_.resting[c].feature.a, state_.resting[c].feature.b})
        if (model_.slot[i] >= 0 && !in_island[i]) in_island[i] = 1, bodies.push_back(i);
    bool all_asleep = true, still = true;
    for (const int i : bodies) {
      all_asleep = all_asleep && state_.asleep[i];
      still = still && t - state_.still_since[i] >= p.sleep_after - 1e-12;
    }
    island.asleep = still && (may_sleep || all_asleep);
    for (const int i : bodies) {
      if (island.asleep == (state_.asleep[i] != 0)) continue;
      changed = true;
      state_.asleep[i] = island.asleep;
      if (island.asleep) {
        state_.bodies[i].P.setZero(), state_.bodies[i].L.setZero();
        state_.static_poses[i] = model_.pose_of(i, state_.bodies[i]);  // (where it stays)
      } else {
        state_.still_since[i] = t;
      }
    }
  }
  for (const int i : dynamic)  // (a body touching nothing falls or floats: awake)
    if (!in_island[i] && state_.asleep[i]) state_.asleep[i] = 0, state_.still_since[i] = t, changed = true;
  return changed;
}

bool World::all_asleep() const {
  return std::all_of(model_.dynamic.begin(), model_.dynamic.end(), [&](int i) { return state_.asleep[i] != 0; });
}

}  // namespace wysiwyf::haptics
