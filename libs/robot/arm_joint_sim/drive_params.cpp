// Reads a drive file (config/robots/puma560_drive.yaml) and converts motor-side values to the
// joint side.
#include "arm_joint_sim/drive_params.hpp"

#include <cmath>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace wysiwyf::robot {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("drive parameters " + path + ": " + what);
}

double number(const YAML::Node& joint, const char* key, const std::string& path, std::size_t index) {
  const YAML::Node v = joint[key];
  if (!v) fail(path, "joints[" + std::to_string(index) + "] has no '" + key + "'");
  try {
    return v.as<double>();
  } catch (const YAML::Exception&) {
    fail(path, "joints[" + std::to_string(index) + "]." + key + " is not a number");
  }
}

}  // namespace

DriveParams DriveParams::ideal(int dof) {
  if (dof < 1 || dof > kMaxArmDof)
    throw std::invalid_argument("ideal drives: need 1.." + std::to_string(kMaxArmDof) + " joints, got " +
                                std::to_string(dof));
  DriveParams d;
  d.gear_ratio = JointVector::Ones(dof);
  d.motor_inertia = d.viscous_friction = d.coulomb_positive = d.coulomb_negative = JointVector::Zero(dof);
  return d;
}

JointVector DriveParams::reflected_inertia() const {
  return (motor_inertia.array() * gear_ratio.array().square()).matrix();
}

JointVector DriveParams::joint_viscous() const {
  return (viscous_friction.array() * gear_ratio.array().square()).matrix();
}

JointVector DriveParams::friction_torque(const JointVector& qd) const {
  JointVector tau(dof());
  for (int j = 0; j < dof(); ++j) {
    const double motor_velocity = gear_ratio[j] * qd[j];
    const double coulomb = motor_velocity > 0.0   ? coulomb_positive[j]
                           : motor_velocity < 0.0 ? coulomb_negative[j]
                                                  : 0.0;
    // Power balance: tau_joint qd = tau_motor (G qd), so tau_joint = G tau_motor.
    tau[j] = gear_ratio[j] * (viscous_friction[j] * motor_velocity + coulomb);
  }
  return tau;
}

JointVector DriveParams::friction_torque(const JointVector& qd, double smoothing) const {
  JointVector tau(dof());
  for (int j = 0; j < dof(); ++j) {
    const double g = gear_ratio[j];
    const double motor_velocity = g * qd[j];
    const double coulomb = (motor_velocity >= 0.0 ? coulomb_positive[j] : -coulomb_negative[j]) *
                           std::tanh(qd[j] / smoothing) * (g >= 0.0 ? 1.0 : -1.0);
    tau[j] = g * (viscous_friction[j] * motor_velocity + coulomb);
  }
  return tau;
}

DriveParams load_drive_params(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    fail(path, "cannot open the file");
  } catch (const YAML::Exception& e) {
    fail(path, std::string("not valid YAML: ") + e.what());
  }
  const YAML::Node joints = root["joints"];
  if (!joints || !joints.IsSequence()) fail(path, "no 'joints' list");
  if (joints.size() < 1 || joints.size() > static_cast<std::size_t>(kMaxArmDof))
    fail(path, "'joints' has " + std::to_string(joints.size()) + " entries, need 1.." + std::to_string(kMaxArmDof));
  const int n = static_cast<int>(joints.size());
  DriveParams d = DriveParams::ideal(n);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const YAML::Node j = joints[i];
    const int k = static_cast<int>(i);
    if (!j["name"]) fail(path, "joints[" + std::to_string(i) + "] has no 'name'");
    d.joint_names.push_back(j["name"].as<std::string>());
    d.gear_ratio[k] = number(j, "gear_ratio", path, i);
    d.motor_inertia[k] = number(j, "motor_inertia", path, i);
    d.viscous_friction[k] = number(j, "viscous_friction", path, i);
    const YAML::Node tc = j["coulomb_friction"];
    if (!tc || !tc.IsSequence() || tc.size() != 2)
      fail(path, "joints[" + std::to_string(i) + "].coulomb_friction must be [Tc+, Tc-]");
    try {
      d.coulomb_positive[k] = tc[0].as<double>();
      d.coulomb_negative[k] = tc[1].as<double>();
    } catch (const YAML::Exception&) {
      fail(path, "joints[" + std::to_string(i) + "].coulomb_friction is not two numbers");
    }
    if (d.gear_ratio[k] == 0.0) fail(path, "joints[" + std::to_string(i) + "].gear_ratio is 0");
    if (d.motor_inertia[k] < 0.0 || d.viscous_friction[k] < 0.0 || d.coulomb_positive[k] < 0.0 ||
        d.coulomb_negative[k] > 0.0)
      fail(path,
           "joints[" + std::to_string(i) + "]: need motor_inertia >= 0, viscous_friction >= 0, Tc+ >= 0 and Tc- <= 0");
  }
  return d;
}

DriveParams load_drive_params(const std::string& path, const std::vector<std::string>& joint_names) {
  DriveParams d = load_drive_params(path);
  if (d.joint_names.size() != joint_names.size())
    fail(path, "'joints' has " + std::to_string(d.joint_names.size()) + " entries, the arm has " +
                   std::to_string(joint_names.size()) + " joints");
  for (std::size_t i = 0; i < joint_names.size(); ++i)
    if (d.joint_names[i] != joint_names[i])
      fail(path, "joints[" + std::to_string(i) + "] is '" + d.joint_names[i] + "', the arm's joint " +
                     std::to_string(i + 1) + " is '" + joint_names[i] + "'");
  return d;
}

}  // namespace wysiwyf::robot
