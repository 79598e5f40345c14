// World (world.hpp): its construction, the step that runs the phases, the state's accessors, and
// where a failed step restarts or holds. The phases live in their own files:
// world_contacts.cpp (contact search and classification), world_forces.cpp (the resting
// contacts' forces and friction), world_integration.cpp (integrating the groups),
// world_groups.cpp (sharing the contacts among the groups), world_impacts.cpp (impacts) and
// world_sleep.cpp (sleeping islands).
#include "rigid_body/world.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "rigid_body/ode_integrator.hpp"

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

World::~World() = default;

void World::set_external_wrench(int body, const Vec3& force, const Vec3& torque) {
  state_.set_wrench(body, force, torque);
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

}  // namespace wysiwyf::haptics
