#pragma once
// A virtual environment as a file (config/scenes/*.yaml): static and dynamic boxes, and where
// the haptic device attaches to a dynamic body (the face the plate is, the F/T sensor behind it,
// the tool mass the sensor carries).
#include <string>
#include <vector>

#include "scene/body.hpp"

namespace wysiwyf::haptics {

struct DeviceAttachment {
  int body = -1;                                                   // the dynamic body the plate is a face of
  std::string face = "+z";                                         // +x -x +y -y +z -z
  Eigen::Isometry3d obj_T_dev = Eigen::Isometry3d::Identity();     // plate frame: z out of the face
  Eigen::Isometry3d dev_T_sensor = Eigen::Isometry3d::Identity();  // F/T sensor frame
  Vec3 knob_offset = Vec3::Zero();                                 // knob tip in the plate frame
  double tool_mass = 0;                                            // kg carried by the sensor (plate, knob)
  Vec3 tool_com = Vec3::Zero();                                    // in the sensor frame
};

struct Scene {
  std::string name;
  Vec3 gravity{0, 0, -9.81};
  std::vector<BodyModel> models;
  std::vector<BodyState> initial;
  DeviceAttachment device;
};

// Reads a scene file; throws std::runtime_error("file:line:col: what; expected ...").
Scene load_scene(const std::string& path);
Scene load_scene_from_string(const std::string& yaml, const std::string& name);

}  // namespace wysiwyf::haptics
