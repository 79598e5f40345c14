#include "rigid_body/world_state.hpp"

#include <algorithm>
#include <utility>

namespace wysiwyf::haptics {

WorldState::WorldState(const WorldModel& model, std::vector<BodyState> initial) : bodies(std::move(initial)) {
  for (auto& s : bodies) s.q.normalize();
  for (std::size_t i = 0; i < bodies.size(); ++i) static_poses.push_back(model.pose_of(static_cast<int>(i), bodies[i]));
  ext_force.assign(bodies.size(), Vec3::Zero());
  ext_torque.assign(bodies.size(), Vec3::Zero());
  still_since.assign(bodies.size(), 0.0);
  asleep.assign(bodies.size(), 0);
}

void WorldState::set_wrench(int body, const Vec3& force, const Vec3& torque) {
  // A new sample is a discontinuity of the right-hand side: the multistep history is invalid.
  // (A change at the level of round-off, from a wrench rotated through a pose, is none.)
  const auto changed = [](const Vec3& a, const Vec3& b) { return (a - b).norm() > 1e-12 * std::max(1.0, b.norm()); };
  if (changed(force, ext_force[body]) || changed(torque, ext_torque[body])) restart = true;
  ext_force[body] = force;
  ext_torque[body] = torque;
}

void WorldState::set_body(const WorldModel& model, int i, const BodyState& s) {
  bodies[i] = s;
  bodies[i].q.normalize();
  static_poses[i] = model.pose_of(i, bodies[i]);
  restart = true;
  wake_all();
}

void WorldState::wake_all() {
  std::fill(asleep.begin(), asleep.end(), 0);
  std::fill(still_since.begin(), still_since.end(), t);
  for (ContactIsland& island : islands) island.asleep = false;
  restart = true;
}

void WorldState::poses_of(const WorldModel& model, const std::vector<BodyState>& states,
                          std::vector<Pose>& poses) const {
  poses = static_poses;  // (static bodies do not move)
  for (int i : model.dynamic) poses[i] = model.pose_of(i, states[i]);
}

double WorldState::energy(const WorldModel& model) const {
  double e = 0;
  for (int i : model.dynamic) {
    const BodyKinematics k(model.bodies[i], bodies[i]);
    e += 0.5 * model.bodies[i].mass * k.v.squaredNorm() + 0.5 * k.omega.dot(bodies[i].L) -
         model.bodies[i].mass * model.params.gravity.dot(bodies[i].x);
  }
  return e;
}

}  // namespace wysiwyf::haptics
