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
  Eigen::Vector2d plate_half{0.1, 0.1};                            // the plate's half size along its x and y, m
  double tool_mass = 0;                                            // kg carried by the sensor (plate, knob)
  Vec3 tool_com = Vec3::Zero();                                    // in the sensor frame
};

// A part of a virtual object that the device's plate can display (paper section 2.3: "buttons
// and knobs", "limited kinds of edges and faces"): where the plate goes to display it, and where
// a finger touches it.
struct DisplayFeature {
  enum class Kind { kFace, kEdge, kKnob };
  std::string name;  // "cube +x knob": how pipelines and scripts name it
  int body = -1;     // a dynamic body of the scene
  std::string face;  // the face the plate lies on: +x -x +y -y +z -z
  Kind kind = Kind::kFace;
  Eigen::Isometry3d obj_T_plate = Eigen::Isometry3d::Identity();  // the plate's frame (z out of the face)
  Vec3 touch = Vec3::Zero();                              // body frame: the touch region's centre (a knob: its tip)
  Vec3 normal = Vec3::UnitZ();                            // body frame: the surface's outward normal there
  Vec3 touch_u = Vec3::UnitX(), touch_v = Vec3::UnitY();  // body frame: the face's in-plane axes
  double half_u = 0, half_v = 0;                          // the touch region's half extents along them (a knob: 0, 0)
  Vec3 face_point = Vec3::Zero();                         // body frame: the face's centre (a point of its plane)
  double knob_radius = 0;                                 // a knob: its radius (drawn by the renderer)

  // The distance from a point (body frame) to the touch region.
  double distance(const Vec3& p) const;
  // Whether a point (body frame) is on the face's outside, from where a finger can touch it.
  bool in_front(const Vec3& p) const { return (p - face_point).dot(normal) >= 0; }
  // How much farther a point (body frame) is out of another face's plane of the box (half_extents:
  // the body's) than out of this feature's face's: 0 in front of this face, growing past the
  // bisector of its edges (beyond an edge, where both faces are as near, it tells them apart).
  double past_edges(const Vec3& p, const Vec3& half_extents) const;
};

struct Scene {
  std::string name;
  Vec3 gravity{0, 0, -9.81};
  std::vector<BodyModel> models;
  std::vector<BodyState> initial;
  DeviceAttachment device;
  std::vector<DisplayFeature> features;

  int body_index(const std::string& name) const;                 // -1 when none
  const DisplayFeature* feature(const std::string& name) const;  // null when none
};

// The frame of a box's face: origin at the face centre, z along its outward normal (body frame).
Eigen::Isometry3d face_frame(const std::string& face, const Vec3& half_extents);

// Reads a scene file; throws std::runtime_error("file:line:col: what; expected ...").
Scene load_scene(const std::string& path);
Scene load_scene_from_string(const std::string& yaml, const std::string& name);

}  // namespace wysiwyf::haptics
