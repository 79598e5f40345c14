// The tool side of the URDF for arm_sim: sensor load and contact shapes; sphere contact tests.
#include "tool_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>

#include "puma_model/urdf_parts.hpp"

namespace wysiwyf::robot::sim {
ToolGeometry load_tool_geometry(const std::string& urdf_path, const ArmModel& model, const std::string& sensor_frame) {
  auto fail = [&](const std::string& what) { throw std::runtime_error("arm_sim: " + urdf_path + ": " + what); };
  {
    std::ifstream in(urdf_path);
    if (!in) fail("cannot open the file");
  }
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(urdf_path);
  if (!urdf) fail("not a valid URDF");
  const FrameId sensor = model.frame(sensor_frame);  // throws for an unknown frame
  const int last = model.dof();                      // the last body: the link after the last joint
  if (model.frame_body(sensor) != last) fail("sensor frame '" + sensor_frame + "' is not fixed to the last link");

  const JointVector zero = JointVector::Zero(last);
  const Eigen::Isometry3d sensor_T_base = model.fk(zero, sensor).inverse();

  ToolGeometry tool;
  // The links below the sensor frame: what the sensor carries.
  std::vector<std::string> below;
  std::function<void(const urdf::LinkConstSharedPtr&)> collect = [&](const urdf::LinkConstSharedPtr& link) {
    for (const auto& child : link->child_links) {
      below.push_back(child->name);
      collect(child);
    }
  };
  const urdf::LinkConstSharedPtr sensor_link = urdf->getLink(sensor_frame);
  if (!sensor_link) fail("no link '" + sensor_frame + "'");
  collect(sensor_link);

  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for (const std::string& name : model.frame_names()) {
    const FrameId f = model.frame(name);
    if (model.frame_body(f) != last) continue;
    const urdf::LinkConstSharedPtr link = urdf->getLink(name);
    if (!link) continue;
    const bool measured = std::find(below.begin(), below.end(), name) != below.end();
    const Eigen::Isometry3d base_T_link = model.fk(zero, f);
    if (measured && link->inertial && link->inertial->mass > 0.0) {
      const Eigen::Vector3d com = sensor_T_base * base_T_link * isometry_of(link->inertial->origin).translation();
      tool.sensor_mass += link->inertial->mass;
      first_moment += link->inertial->mass * com;
    }
    for (const auto& collision : link->collision_array) {
      if (!collision || !collision->geometry) continue;
      ContactShape s;
      s.link = name;
      s.measured = measured;
      s.sensor_T_shape = sensor_T_base * base_T_link * isometry_of(collision->origin);
      double extent = 0.0;
      switch (collision->geometry->type) {
        case urdf::Geometry::BOX: {
          const auto& box = static_cast<const urdf::Box&>(*collision->geometry);
          s.kind = ContactShape::Kind::kBox;
          s.half_extents = 0.5 * Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
          extent = s.half_extents.norm();
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& cyl = static_cast<const urdf::Cylinder&>(*collision->geometry);
          s.kind = ContactShape::Kind::kCylinder;
          s.radius = cyl.radius;
          s.half_length = 0.5 * cyl.length;
          extent = std::hypot(s.radius, s.half_length);
          break;
        }
        case urdf::Geometry::SPHERE: {
          s.kind = ContactShape::Kind::kSphere;
          s.radius = static_cast<const urdf::Sphere&>(*collision->geometry).radius;
          extent = s.radius;
          break;
        }
        default: continue;  // meshes: not simulated for contact
      }
      tool.bounding_radius = std::max(tool.bounding_radius, s.sensor_T_shape.translation().norm() + extent);
      tool.shapes.push_back(s);
    }
  }
  if (tool.sensor_mass > 0.0) tool.sensor_com = first_moment / tool.sensor_mass;
  return tool;
}

bool sphere_contact(const ContactShape& shape, const Eigen::Isometry3d& base_T_shape, const Eigen::Vector3d& c,
                    double r, double& depth, Eigen::Vector3d& normal, Eigen::Vector3d& point) {
  const Eigen::Matrix3d& R = base_T_shape.linear();
  const Eigen::Vector3d p = R.transpose() * (c - base_T_shape.translation());  // centre in the shape frame
  Eigen::Vector3d closest = Eigen::Vector3d::Zero(), n_local = Eigen::Vector3d::UnitZ();
  bool inside = false;
  double inside_depth = 0.0;
  switch (shape.kind) {
    case ContactShape::Kind::kSphere: {
      const double d = p.norm();
      if (d >= shape.radius + r) return false;
      n_local = d > 1e-12 ? Eigen::Vector3d(p / d) : Eigen::Vector3d::UnitZ();
      closest = shape.radius * n_local;
      depth = shape.radius + r - d;
      normal = R * n_local;
      point = base_T_shape * closest;
      return true;
    }
    case ContactShape::Kind::kBox: {
      const Eigen::Vector3d& h = shape.half_extents;
      closest = p.cwiseMax(-h).cwiseMin(h);
      if (closest == p) {  // centre inside: leave through the nearest face
        inside = true;
        int axis = 0;
        double best = h[0] - std::abs(p[0]);
        for (int i = 1; i < 3; ++i)
          if (h[i] - std::abs(p[i]) < best) best = h[i] - std::abs(p[i]), axis = i;
        n_local = Eigen::Vector3d::Zero();
        n_local[axis] = p[axis] >= 0.0 ? 1.0 : -1.0;
        closest[axis] = n_local[axis] * h[axis];
        inside_depth = best;
      }
      break;
    }
    case ContactShape::Kind::kCylinder: {
      const double rho = std::hypot(p.x(), p.y());
      const double hl = shape.half_length;
      const Eigen::Vector2d radial =
          rho > 1e-12 ? Eigen::Vector2d(p.x() / rho, p.y() / rho) : Eigen::Vector2d(1.0, 0.0);
      closest = Eigen::Vector3d(p.x(), p.y(), std::clamp(p.z(), -hl, hl));
      if (rho > shape.radius) closest.head<2>() = shape.radius * radial;
      if (rho <= shape.radius && std::abs(p.z()) <= hl) {  // inside: nearest of side and caps
        inside = true;
        const double side = shape.radius - rho, cap = hl - std::abs(p.z());
        if (side < cap) {
          n_local = Eigen::Vector3d(radial.x(), radial.y(), 0.0);
          closest = Eigen::Vector3d(shape.radius * radial.x(), shape.radius * radial.y(), p.z());
          inside_depth = side;
        } else {
          n_local = Eigen::Vector3d(0.0, 0.0, p.z() >= 0.0 ? 1.0 : -1.0);
          closest = Eigen::Vector3d(p.x(), p.y(), n_local.z() * hl);
          inside_depth = cap;
        }
      }
      break;
    }
  }
  if (inside) {
    depth = inside_depth + r;
  } else {
    const Eigen::Vector3d d = p - closest;
    const double dist = d.norm();
    if (dist >= r) return false;
    n_local = dist > 1e-12 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d::UnitZ();
    depth = r - dist;
  }
  normal = R * n_local;
  point = base_T_shape * closest;
  return true;
}

}  // namespace wysiwyf::robot::sim
