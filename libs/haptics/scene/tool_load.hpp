#pragma once
// From what the wrist F/T sensor measures to the wrench the user applies to the virtual object
// (paper section 4.3, STEP 1). The sensor reports, in its own frame and about its origin, the
// load on its tool side: the user's push plus the weight of the tool it carries.
#include <Eigen/Geometry>

#include "scene/body.hpp"
#include "scene/scene.hpp"

namespace wysiwyf::haptics {

struct SensorReading {
  Vec3 force = Vec3::Zero();   // N, sensor frame
  Vec3 torque = Vec3::Zero();  // N.m, sensor frame, about the sensor origin
};

struct BodyWrench {
  Vec3 force = Vec3::Zero();   // N, world frame
  Vec3 torque = Vec3::Zero();  // N.m, world frame, about the body's centre of mass
};

// The user's load alone, in the sensor frame: the reading less the weight of the tool it carries
// (world_R_sensor: the sensor's orientation; tool_com_sensor: the tool's centre of mass).
inline SensorReading user_load(const SensorReading& measured, const Mat3& world_R_sensor, double tool_mass,
                               const Vec3& tool_com_sensor, const Vec3& gravity) {
  const Vec3 weight_sensor = world_R_sensor.transpose() * (tool_mass * gravity);
  return SensorReading{measured.force - weight_sensor, measured.torque - tool_com_sensor.cross(weight_sensor)};
}

// world_T_sensor: where the sensor is; body_com: the body's centre of mass (world).
inline BodyWrench user_wrench_on_body(const SensorReading& measured, const Eigen::Isometry3d& world_T_sensor,
                                      const Vec3& body_com, double tool_mass, const Vec3& tool_com_sensor,
                                      const Vec3& gravity) {
  const Mat3 R = world_T_sensor.linear();
  const SensorReading user = user_load(measured, R, tool_mass, tool_com_sensor, gravity);
  BodyWrench w;
  w.force = R * user.force;
  w.torque = R * user.torque + (world_T_sensor.translation() - body_com).cross(w.force);
  return w;
}

// The user's load alone for the scene's device with its plate at base_T_dev (the sensor at
// base_T_dev * dev_T_sensor, carrying the device's tool).
inline SensorReading user_load(const SensorReading& measured, const Eigen::Isometry3d& base_T_dev,
                               const DeviceAttachment& device, const Vec3& gravity) {
  return user_load(measured, base_T_dev.linear() * device.dev_T_sensor.linear(), device.tool_mass, device.tool_com,
                   gravity);
}

}  // namespace wysiwyf::haptics
