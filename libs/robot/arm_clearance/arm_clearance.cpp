#include "arm_clearance/arm_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace wysiwyf::robot {

using Vec3 = Eigen::Vector3d;

ArmClearance::ArmClearance(const ArmModel& model) : model_(model) {
  std::map<std::pair<std::string, ShapeType>, int> count;  // shapes of one type per link, to number them
  for (const CollisionShape& c : model.collision_shapes())
    if (c.supported()) ++count[{c.link, c.type}];
  std::map<std::pair<std::string, ShapeType>, int> seen;
  for (const CollisionShape& c : model.collision_shapes()) {
    if (!c.supported()) continue;  // a mesh: ArmModel::collision_notes() says so
    Part p;
    p.body = c.body;
    p.body_T_shape = c.body_T_shape;
    p.type = c.type;
    p.half = 0.5 * c.box_size;
    p.radius = c.radius;
    p.half_length = 0.5 * c.length;
    parts_.push_back(p);
    std::string name = c.link + " " + to_string(c.type);
    if (count[{c.link, c.type}] > 1) name += " " + std::to_string(++seen[{c.link, c.type}]);
    names_.push_back(std::move(name));
    if (std::find(bodies_.begin(), bodies_.end(), c.body) == bodies_.end()) bodies_.push_back(c.body);
  }
  if (parts_.empty())
    throw std::invalid_argument(model.urdf_path() +
                                ": no <collision> box, cylinder or sphere on any link; the arm's clearance to a "
                                "hand is measured from them");
  out_.resize(parts_.size());
  for (std::size_t i = 0; i < parts_.size(); ++i) out_[i].name = names_[i].c_str();
}

ArmClearance::ArmClearance(const ArmClearance& other)
    : model_(other.model_), parts_(other.parts_), names_(other.names_), bodies_(other.bodies_), out_(other.out_) {
  for (std::size_t i = 0; i < parts_.size(); ++i) out_[i].name = names_[i].c_str();
}

Vec3 ArmClearance::nearest_point(const Part& part, const Eigen::Isometry3d& base_T_shape, const Vec3& point) {
  const Vec3 p = base_T_shape.inverse() * point;  // in the shape's frame
  Vec3 n = p;
  switch (part.type) {
    case ShapeType::kBox: n = p.cwiseMax(-part.half).cwiseMin(part.half); break;
    case ShapeType::kCylinder: {
      const double rho = p.head<2>().norm();
      if (rho > part.radius) n.head<2>() *= part.radius / rho;
      n.z() = std::clamp(p.z(), -part.half_length, part.half_length);
      break;
    }
    case ShapeType::kSphere: {
      const double d = p.norm();
      if (d > part.radius) n *= part.radius / d;
      break;
    }
    case ShapeType::kMesh: break;  // never a part
  }
  if (n == p) return point;  // inside (nothing clamped): the point itself, its distance exactly 0
  return base_T_shape * n;
}

const std::vector<PartClearance>& ArmClearance::evaluate(const JointRef& q, const JointRef& qd,
                                                         const Vec3& point) const {
  if (qd.size() != model_.dof())
    throw std::invalid_argument("ArmClearance::evaluate: qd has " + std::to_string(qd.size()) + " values, the arm " +
                                std::to_string(model_.dof()) + " joints");
  for (int body : bodies_) {
    const auto b = static_cast<std::size_t>(body);
    base_T_body_[b] = model_.fk(q, model_.body_frame(body));
    body_twist_[b] = model_.jacobian(q, model_.body_frame(body)) * qd;
  }
  for (std::size_t i = 0; i < parts_.size(); ++i) {
    const Part& part = parts_[i];
    const auto b = static_cast<std::size_t>(part.body);
    PartClearance& c = out_[i];
    c.nearest = nearest_point(part, base_T_body_[b] * part.body_T_shape, point);
    const Vec3 to_point = point - c.nearest;
    c.distance = to_point.norm();
    // A rigid body's velocity field: v(x) = v_origin + w x (x - origin).
    const Vec3 v = body_twist_[b].head<3>() + body_twist_[b].tail<3>().cross(c.nearest - base_T_body_[b].translation());
    c.approach_speed = c.distance > 1e-9 ? v.dot(to_point / c.distance) : v.norm();
  }
  return out_;
}

const PartClearance& ArmClearance::nearest(const std::vector<PartClearance>& parts) {
  return *std::min_element(parts.begin(), parts.end(),
                           [](const PartClearance& a, const PartClearance& b) { return a.distance < b.distance; });
}

}  // namespace wysiwyf::robot
