#pragma once
// The flat state vector the integrator integrates: 13 numbers per dynamic body, in the order of the
// world's dynamic-body list: x(3) q(4: w x y z) P(3) L(3); and its time derivative, laid out
// the same way.
#include <vector>

#include "scene/body.hpp"

namespace wysiwyf::haptics {

constexpr int kStateSize = 13;  // per dynamic body

// Writes the states of the bodies listed in `dynamic` into y.
void pack_state(const std::vector<BodyState>& states, const std::vector<int>& dynamic, double* y);
// Reads them back from y into `states`; the other bodies' entries are left as they are.
void unpack_state(const double* y, const std::vector<int>& dynamic, std::vector<BodyState>& states);
// One body's state from its 13 numbers at o.
inline BodyState unpack_body(const double* o) {
  return BodyState{Vec3(o[0], o[1], o[2]), Quat(o[3], o[4], o[5], o[6]), Vec3(o[7], o[8], o[9]),
                   Vec3(o[10], o[11], o[12])};
}

// One body's 13 derivatives at d: velocity v, the quaternion's rate under angular velocity
// omega, force and torque (the momenta's rates).
inline void write_derivative(const Vec3& v, const Vec3& omega, const Quat& q, const Vec3& force, const Vec3& torque,
                             double* d) {
  d[0] = v.x(), d[1] = v.y(), d[2] = v.z();
  // dq/dt = 1/2 (0, omega) q
  d[3] = -0.5 * omega.dot(q.vec());
  const Vec3 qv = 0.5 * (q.w() * omega + omega.cross(q.vec()));
  d[4] = qv.x(), d[5] = qv.y(), d[6] = qv.z();
  d[7] = force.x(), d[8] = force.y(), d[9] = force.z();
  d[10] = torque.x(), d[11] = torque.y(), d[12] = torque.z();
}

}  // namespace wysiwyf::haptics
