#pragma once
// A rigid box in Baraff's state form: position x, orientation q, linear momentum P, angular
// momentum L (world frame). The model (mass, inertia, size, surface) is constant; the state moves.
#include <Eigen/Geometry>

#include <array>
#include <string>

namespace wysiwyf::haptics {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

struct BodyModel {
  std::string name;
  bool dynamic = true;  // false: fixed in the world (table, walls)
  Vec3 half_extents{0.1, 0.1, 0.1};
  double mass = 1.0;                     // kg
  Mat3 inertia_body = Mat3::Identity();  // about the centre of mass, body axes
  double restitution = 0.0;              // Newton's coefficient, eq. (12)
  double friction = 0.0;                 // Coulomb coefficient; a contact uses the larger of its two bodies'

  // Solid box of uniform density.
  static Mat3 box_inertia(double mass, const Vec3& half_extents);
};

struct BodyState {
  Vec3 x = Vec3::Zero();
  Quat q = Quat::Identity();
  Vec3 P = Vec3::Zero();
  Vec3 L = Vec3::Zero();
};

// The body's pose in the world, world_T_body (q normalised: the integrator lets it drift).
inline Eigen::Isometry3d pose_of(const BodyState& s) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = s.q.normalized().toRotationMatrix();
  T.translation() = s.x;
  return T;
}

// What follows from a state: velocities, rotation, world inverse inertia.
struct BodyKinematics {
  Mat3 R;
  Vec3 v;
  Vec3 omega;
  Mat3 inv_inertia_world;  // zero for static bodies
  double inv_mass = 0;     // zero for static bodies

  BodyKinematics(const BodyModel& m, const BodyState& s);
  // With the body-frame inverse inertia already at hand (the simulation's inner loop).
  BodyKinematics(const BodyModel& m, const BodyState& s, const Mat3& inv_inertia_body);
  Vec3 point_velocity(const Vec3& p, const Vec3& x) const { return v + omega.cross(p - x); }
};

// The 8 corners, 12 edges (as corner index pairs) and 6 faces (outward normal, offset) of a box.
struct BoxTopology {
  static const std::array<Vec3, 8>& corner_signs();
  static const std::array<std::array<int, 2>, 12>& edges();
  static Vec3 corner(const Vec3& half, int i) { return corner_signs()[i].cwiseProduct(half); }
};

}  // namespace wysiwyf::haptics
