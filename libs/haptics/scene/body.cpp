#include "scene/body.hpp"

namespace wysiwyf::haptics {

Mat3 BodyModel::box_inertia(double mass, const Vec3& h) {
  const Vec3 s = 4.0 * h.cwiseProduct(h);  // (2h)^2
  return (mass / 12.0 * Vec3(s.y() + s.z(), s.x() + s.z(), s.x() + s.y())).asDiagonal();
}

BodyKinematics::BodyKinematics(const BodyModel& m, const BodyState& s)
    : BodyKinematics(m, s, m.dynamic ? Mat3(m.inertia_body.inverse()) : Mat3::Zero()) {}

BodyKinematics::BodyKinematics(const BodyModel& m, const BodyState& s, const Mat3& inv_inertia_body)
    : R(s.q.normalized().toRotationMatrix()) {
  if (!m.dynamic) {
    v.setZero();
    omega.setZero();
    inv_inertia_world.setZero();
    return;
  }
  inv_mass = 1.0 / m.mass;
  inv_inertia_world = R * inv_inertia_body * R.transpose();
  v = s.P * inv_mass;
  omega = inv_inertia_world * s.L;
}

const std::array<Vec3, 8>& BoxTopology::corner_signs() {
  static const std::array<Vec3, 8> c = {Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(1, 1, -1),
                                        Vec3(-1, -1, 1),  Vec3(1, -1, 1),  Vec3(-1, 1, 1),  Vec3(1, 1, 1)};
  return c;
}

const std::array<std::array<int, 2>, 12>& BoxTopology::edges() {
  // Corners differing in one sign: along x (0-1, 2-3, 4-5, 6-7), y (0-2, 1-3, 4-6, 5-7), z (0-4, 1-5, 2-6, 3-7).
  static const std::array<std::array<int, 2>, 12> e = {
      {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};
  return e;
}

}  // namespace wysiwyf::haptics
