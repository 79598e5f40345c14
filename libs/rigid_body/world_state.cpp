#include "rigid_body/world_state.hpp"

namespace wysiwyf::haptics {

WorldState::WorldState(const WorldModel& model, std::vector<BodyState> initial) : bodies(std::move(initial)) {
  for (auto& s : bodies) s.q.normalize();
  for (std::size_t i = 0; i < bodies.size(); ++i) static_poses.push_back(model.pose_of(static_cast<int>(i), bodies[i]));
  ext_force.assign(bodies.size(), Vec3::Zero());
  ext_torque.assign(bodies.size(), Vec3::Zero());
}

}  // namespace wysiwyf::haptics
