#pragma once
// From what the wrist F/T sensor measures to the wrench the user applies to the virtual object
// (paper section 4.3, STEP 1). The sensor reports, in its own frame and about its origin, the
// load on its tool side: the user's push plus the weight of the tool it carries.
#include <Eigen/Geometry>

#include "scene/body.hpp"

namespace wysiwyf::haptics {

struct SensorReading {
  Vec3 force = Vec3::Zero();   // N, sensor frame
  Vec3 torque = Vec3::Zero();  // N.m, sensor frame, about the sensor origin
};

struct BodyWrench {
  Vec3 force = Vec3::Zero();   // N, world frame
  Vec3 torque = Vec3::Zero();  // N.m, world frame, about the body's centre of mass
};

// world_T_sensor: where the sensor is; body_com: the body's centre of mass (world).
inline BodyWrench user_wrench_on_body(const SensorReading& measured, const Eigen::Isometry3d& world_T_sensor,
                                      const Vec3& body_com, double tool_mass, const Vec3& tool_com_sensor,
                                      const Vec3& gravity) {
  const Mat3 R = world_T_sensor.linear();
  // The tool's weight, as the sensor sees it: remove it.
  const Vec3 weight_sensor = R.transpose() * (tool_mass * gravity);
  const Vec3 f_user = measured.force - weight_sensor;
  const Vec3 t_user = measured.torque - tool_com_sensor.cross(weight_sensor);
  BodyWrench w;
  w.force = R * f_user;
  w.torque = R * t_user + (world_T_sensor.translation() - body_com).cross(w.force);
  return w;
}

}  // namespace wysiwyf::haptics
