// World's integration of a step (world.hpp): the contacts classified, the integration groups
// formed and each awake group integrated to the step's end, stopping at each impact.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "rigid_body/arkode_integrator.hpp"
#include "rigid_body/cvode_integrator.hpp"
#include "rigid_body/state_vector.hpp"
#include "rigid_body/world.hpp"

namespace wysiwyf::haptics {

std::unique_ptr<OdeIntegrator> World::make_integrator(int bodies) {
  const WorldParams& p = model_.params;
  const IntegratorOptions options{
      p.rtol, p.atol, p.initial_step, p.restart_growth, p.nonlinear_convergence, p.max_integrator_steps};
  const int size = kStateSize * std::max(1, bodies);
  if (p.integrator == Integrator::kAdams) return std::make_unique<CvodeIntegrator>(size, options, *this);
  return std::make_unique<ArkodeIntegrator>(size, options, *this);
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
    work_.share.all_resting.swap(state_.resting);
    work_.share.all_islands.swap(state_.islands);
    work_.share.all_watched.swap(state_.watched);
    work_.share.all_gaps.swap(state_.watched_gaps);
    work_.share.all_gaps.resize(work_.share.all_watched.size());  // (stale where restarting: found again)
    work_.share.watched_gone.assign(work_.share.all_watched.size(), 0);
    work_.share.island_replaced.assign(work_.share.all_islands.size(), 0);
    work_.share.joined_resting.clear();
    work_.share.joined_islands.clear();
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
    state_.watched_gaps.swap(work_.impacts.gaps_at_step_end);
  }
}

}  // namespace wysiwyf::haptics
