#include "arm_clearance/arm_clearance.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::robot {

namespace {

using Vec3 = Eigen::Vector3d;

// A point's velocity on the segment a-b of a rigid link, from the ends' velocities (a rigid
// body's velocity field is affine in position).
struct Segment {
  Vec3 a, b, va, vb;
};

PartClearance capsule(const char* name, const Segment& s, double radius, const Vec3& p) {
  const Vec3 ab = s.b - s.a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - s.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  PartClearance c;
  c.name = name;
  c.nearest = s.a + t * ab;
  const Vec3 to_point = p - c.nearest;
  const double d = to_point.norm();
  c.distance = std::max(0.0, d - radius);
  const Vec3 v = s.va + t * (s.vb - s.va);
  c.approach_speed = d > 1e-9 ? v.dot(to_point / d) : v.norm();
  return c;
}

}  // namespace

ArmClearance::ArmClearance(const PumaModel& model, Eigen::Vector2d plate_half, double knob_length, double knob_radius)
    : model_(model),
      link1_(model.frame("link1")),
      link3_(model.frame("link3")),
      link4_(model.frame("link4")),
      flange_(model.frame("flange")),
      dev_(model.frame("dev")),
      plate_half_(plate_half),
      knob_length_(knob_length),
      knob_radius_(knob_radius) {}

std::array<PartClearance, ArmClearance::kParts> ArmClearance::evaluate(const Vector6d& q, const Vector6d& qd,
                                                                       const Vec3& point) const {
  // Each frame's origin and its velocity (the first three rows of its geometric Jacobian).
  auto at = [&](FrameId f, Vec3& p, Vec3& v, Vec3* w = nullptr, Eigen::Matrix3d* R = nullptr) {
    const Eigen::Isometry3d T = model_.fk(q, f);
    const Vector6d twist = model_.jacobian(q, f) * qd;
    p = T.translation();
    v = twist.head<3>();
    if (w) *w = twist.tail<3>();
    if (R) *R = T.linear();
  };
  Vec3 p1, v1, p3, v3, p4, v4, pf, vf, pd, vd, wd;
  Eigen::Matrix3d Rd;
  at(link1_, p1, v1);
  at(link3_, p3, v3);
  at(link4_, p4, v4);
  at(flange_, pf, vf);
  at(dev_, pd, vd, &wd, &Rd);
  std::array<PartClearance, kParts> out;
  out[0] = capsule("upper arm", {p1, p3, v1, v3}, 0.07, point);
  out[1] = capsule("forearm", {p3, p4, v3, v4}, 0.055, point);
  out[2] = capsule("wrist", {p4, pf, v4, vf}, 0.04, point);
  out[3] = capsule("sensor", {pf, pd, vf, vd}, 0.04, point);
  // The plate: a rectangle in dev's x-y plane (its thickness, 1 cm behind z = 0, ignored).
  {
    const Vec3 local = Rd.transpose() * (point - pd);
    const Vec3 on_plate(std::clamp(local.x(), -plate_half_.x(), plate_half_.x()),
                        std::clamp(local.y(), -plate_half_.y(), plate_half_.y()), 0.0);
    PartClearance& c = out[4];
    c.name = "plate";
    c.nearest = pd + Rd * on_plate;
    const Vec3 to_point = point - c.nearest;
    c.distance = to_point.norm();
    const Vec3 v = vd + wd.cross(c.nearest - pd);
    c.approach_speed = c.distance > 1e-9 ? v.dot(to_point / c.distance) : v.norm();
  }
  const Vec3 tip = pd + Rd.col(2) * knob_length_;
  out[5] = capsule("knob", {pd, tip, vd, vd + wd.cross(tip - pd)}, knob_radius_, point);
  return out;
}

const PartClearance& ArmClearance::nearest(const std::array<PartClearance, kParts>& parts) {
  return *std::min_element(parts.begin(), parts.end(),
                           [](const PartClearance& a, const PartClearance& b) { return a.distance < b.distance; });
}

}  // namespace wysiwyf::robot
