#include "rigid_body/world_model.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace wysiwyf::haptics {

WorldModel::WorldModel(std::vector<BodyModel> bodies_in, const WorldParams& params_in)
    : bodies(std::move(bodies_in)), params(params_in) {
  if (!(params.rtol >= 0) || !(params.atol > 0))
    throw std::invalid_argument("World: tolerances rtol >= 0 and atol > 0 expected, got rtol " +
                                std::to_string(params.rtol) + ", atol " + std::to_string(params.atol));
  if (!(params.contact_tolerance > 0) || !(params.contact_release >= params.contact_tolerance))
    throw std::invalid_argument("World: contact_tolerance > 0 and contact_release >= contact_tolerance expected, got " +
                                std::to_string(params.contact_tolerance) + " and " +
                                std::to_string(params.contact_release) + " m");
  slot.assign(bodies.size(), -1);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const auto& m = bodies[i];
    if ((m.half_extents.array() <= 0).any())
      throw std::invalid_argument("body '" + m.name + "': half extents must be positive");
    if (m.dynamic && !(m.mass > 0)) throw std::invalid_argument("body '" + m.name + "': mass must be positive");
    if (m.restitution < 0 || m.restitution > 1)
      throw std::invalid_argument("body '" + m.name + "': restitution must be within [0, 1]");
    if (m.dynamic) {
      slot[i] = static_cast<int>(dynamic.size());
      dynamic.push_back(static_cast<int>(i));
    }
  }
  for (const auto& m : bodies) inv_inertia_body.push_back(m.dynamic ? Mat3(m.inertia_body.inverse()) : Mat3::Zero());
}

Pose WorldModel::pose_of(int i, const BodyState& s) const {
  const BodyKinematics k(bodies[i], s, inv_inertia_body[i]);
  return Pose{s.x, k.R, k.v, k.omega, k.inv_mass, k.inv_inertia_world};
}

}  // namespace wysiwyf::haptics
