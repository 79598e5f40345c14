#pragma once
// Pieces every reader of a URDF through urdfdom needs (PumaModel, ArmModel, arm_sim's tool side):
// a urdf::Pose as an isometry, a joint type's name for errors, the merging of links' inertias
// into one rigid body, and a model's named frames looked up. Include it only where urdfdom is linked.
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <urdf_model/joint.h>
#include <urdf_model/pose.h>

#include "puma_model/types.hpp"

namespace wysiwyf::robot {

// parent_T_child from a URDF origin (its quaternion normalised).
inline Eigen::Isometry3d isometry_of(const urdf::Pose& pose) {
  double x, y, z, w;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return T;
}

// "revolute", "fixed", ...: a URDF joint type as the file writes it.
inline const char* joint_type_name(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

// Accumulates rigid bodies (mass, first moment, inertia about the body origin).
struct InertiaSum {
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d about_origin = Eigen::Matrix3d::Zero();

  // A body of mass m at com (body frame) with inertia_at_com about its centre, body axes.
  void add(double m, const Eigen::Vector3d& com, const Eigen::Matrix3d& inertia_at_com) {
    mass += m;
    first_moment += m * com;
    about_origin += inertia_at_com + m * (com.squaredNorm() * Eigen::Matrix3d::Identity() - com * com.transpose());
  }
  // The sum as one body: its mass, centre and inertia about that centre (symmetrised).
  BodyInertia body() const {
    BodyInertia b;
    b.mass = mass;
    if (mass > 0.0) {
      b.com = first_moment / mass;
      b.inertia = about_origin - mass * (b.com.squaredNorm() * Eigen::Matrix3d::Identity() - b.com * b.com.transpose());
    } else {
      b.inertia = about_origin;
    }
    b.inertia = 0.5 * (b.inertia + b.inertia.transpose());
    return b;
  }
};

// The id of the frame called `name` among a model's `frames` (each with a `name`); throws
// std::out_of_range naming the model, the file and the frames it has.
template <class Frames>
FrameId frame_named(const Frames& frames, const std::string& name, const char* model, const std::string& path) {
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames[i].name == name) return FrameId{static_cast<int>(i)};
  std::string known;
  for (const auto& f : frames) known += (known.empty() ? "" : ", ") + f.name;
  throw std::out_of_range(std::string(model) + ": no frame '" + name + "' in " + path + " (frames: " + known + ")");
}

// Every frame's name, in order.
template <class Frames>
std::vector<std::string> frame_names_of(const Frames& frames) {
  std::vector<std::string> names;
  names.reserve(frames.size());
  for (const auto& f : frames) names.push_back(f.name);
  return names;
}

}  // namespace wysiwyf::robot
