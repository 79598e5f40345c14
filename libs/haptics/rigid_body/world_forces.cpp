// World's resting-contact forces (world.hpp): the resting contacts evaluated at a state, their
// friction found once a step and held through it, and the right-hand side, whose normal forces
// come from the LCP of eqs. (9)-(10) at every evaluation.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "rigid_body/contact_system.hpp"
#include "rigid_body/ode_integrator.hpp"
#include "rigid_body/state_vector.hpp"
#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

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

}  // namespace wysiwyf::haptics
