#pragma once
// What arm_sim needs of the tool side of the URDF that ArmModel merges into the last body: the
// mass the wrist F/T sensor carries (every link below the sensor frame) and the collision shapes
// of the links fixed to the last link (the plate, the knob, the sensor housing), for penalty
// contact with the user's fingertip. Any serial arm's URDF with the tool frames on its flange.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot::sim {

struct ContactShape {
  enum class Kind { kBox, kCylinder, kSphere };
  Kind kind = Kind::kBox;
  std::string link;                                                  // the URDF link it belongs to
  Eigen::Isometry3d sensor_T_shape = Eigen::Isometry3d::Identity();  // centre and axes (cylinder: z)
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();            // box
  double radius = 0.0;                                               // cylinder, sphere
  double half_length = 0.0;                                          // cylinder
  bool measured = false;  // beyond the F/T sensor: its contact forces pass through the sensor
};

struct ToolGeometry {
  double sensor_mass = 0.0;                              // kg carried by the sensor
  Eigen::Vector3d sensor_com = Eigen::Vector3d::Zero();  // its centre of mass, sensor frame
  std::vector<ContactShape> shapes;
  double bounding_radius = 0.0;  // every shape lies within this distance of the sensor origin
};

// Reads the URDF again (urdfdom) for what the model does not keep. `sensor_frame` must be fixed
// to the last link. Throws std::runtime_error naming the file and what is wrong.
ToolGeometry load_tool_geometry(const std::string& urdf_path, const ArmModel& model, const std::string& sensor_frame);

// A sphere (centre c, radius r, base frame) against a shape placed at base_T_shape. On contact
// returns true with the depth of penetration (> 0), the unit normal pointing out of the shape
// towards the sphere, and the contact point on the shape's surface.
bool sphere_contact(const ContactShape& shape, const Eigen::Isometry3d& base_T_shape, const Eigen::Vector3d& c,
                    double r, double& depth, Eigen::Vector3d& normal, Eigen::Vector3d& point);

}  // namespace wysiwyf::robot::sim
