#include "wrist_calibration/wrist_readings_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "wrist_calibration/wrist_poses.hpp"

namespace wysiwyf::robot {

namespace {

constexpr std::size_t kMaxSamples = 10000;

[[noreturn]] void fail(const std::string& file, const YAML::Node& n, const std::string& what) {
  const YAML::Mark m = n.Mark();
  throw std::runtime_error(file + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1) + ": " + what);
}

Eigen::VectorXd numbers(const std::string& file, const YAML::Node& n, const std::string& what, std::size_t count) {
  if (!n.IsSequence() || n.size() != count)
    fail(file, n, what + ": expected a list of " + std::to_string(count) + " numbers");
  Eigen::VectorXd v(static_cast<Eigen::Index>(count));
  for (std::size_t i = 0; i < count; ++i) {
    double x = NAN;
    try {
      if (n[i].IsScalar()) x = n[i].as<double>();
    } catch (const YAML::Exception&) {
    }
    if (!std::isfinite(x))
      fail(file, n[i],
           what + ": found '" + (n[i].IsScalar() ? n[i].Scalar() : std::string("a non-scalar")) +
               "'; expected a finite number");
    v[static_cast<Eigen::Index>(i)] = x;
  }
  return v;
}

std::vector<WristSample> parse(const YAML::Node& root, const std::string& file, int joints) {
  if (!root.IsMap() || !root["readings"])
    fail(file, root, "expected a map with readings: [{joints: [...], wrench: [fx, fy, fz, tx, ty, tz]}, ...]");
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it->first.Scalar() != "readings")
      fail(file, it->first, "unknown key '" + it->first.Scalar() + "'; expected readings");
  const YAML::Node list = root["readings"];
  if (!list.IsSequence()) fail(file, list, "readings: expected a list of {joints, wrench}");
  if (list.size() > kMaxSamples)
    fail(file, list, "readings: " + std::to_string(list.size()) + " samples; expected at most 10000");
  std::vector<WristSample> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node r = list[i];
    const std::string where = "readings[" + std::to_string(i) + "]";
    if (!r.IsMap()) fail(file, r, where + ": expected a map {label, joints, wrench}");
    for (auto it = r.begin(); it != r.end(); ++it) {
      const std::string k = it->first.Scalar();
      if (k != "label" && k != "joints" && k != "wrench")
        fail(file, it->first, where + ": unknown key '" + k + "'; expected label, joints, wrench");
    }
    if (!r["joints"] || !r["wrench"]) fail(file, r, where + ": expected both joints and wrench");
    WristSample s;
    if (r["label"]) {
      if (!r["label"].IsScalar() || r["label"].Scalar().size() > 64)
        fail(file, r["label"], where + " label: expected a text of at most 64 characters");
      s.label = r["label"].Scalar();
    } else {
      s.label = "pose " + std::to_string(i + 1);
    }
    s.joints = numbers(file, r["joints"], where + " joints", static_cast<std::size_t>(joints));
    s.wrench = numbers(file, r["wrench"], where + " wrench (fx fy fz N, tx ty tz N m)", 6);
    out.push_back(s);
  }
  return out;
}

}  // namespace

std::vector<WristSample> load_wrist_readings_from_string(const std::string& yaml, const std::string& name, int joints) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                             ": not YAML: " + e.msg);
  }
  return parse(root, name, joints);
}

std::vector<WristSample> load_wrist_readings(const std::string& path, int joints) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the wrist readings file");
  std::stringstream text;
  text << in.rdbuf();
  return load_wrist_readings_from_string(text.str(), path, joints);
}

std::string wrist_readings_yaml(const std::vector<WristSample>& samples) {
  std::string s = "readings:\n";
  char buf[64];
  for (const WristSample& w : samples) {
    std::string label = w.label;  // quoted: a quote or backslash in it would end the string
    for (char& c : label)
      if (c == '"' || c == '\\') c = '\'';
    s += "  - label: \"" + label + "\"\n    joints: [";
    for (Eigen::Index i = 0; i < w.joints.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%s%.9g", i ? ", " : "", w.joints[i]);
      s += buf;
    }
    s += "]\n    wrench: [";
    for (int i = 0; i < 6; ++i) {
      std::snprintf(buf, sizeof buf, "%s%.9g", i ? ", " : "", w.wrench[i]);
      s += buf;
    }
    s += "]\n";
  }
  return s;
}

std::vector<WristReading> wrist_readings(const ArmModel& arm, FrameId f, const std::vector<WristSample>& samples,
                                         const Eigen::Vector3d& gravity_base) {
  std::vector<WristReading> out;
  for (const WristSample& s : samples) {
    if (s.joints.size() != arm.dof() || !arm.limits().within(s.joints, 1e-6))
      throw std::invalid_argument(s.label + ": joints outside the limits of " + arm.urdf_path() +
                                  "; expected a pose the arm can take");
    WristReading r;
    r.label = s.label;
    r.gravity_sensor = gravity_in_frame(arm, s.joints, f, gravity_base);
    r.force = s.wrench.head<3>();
    r.torque = s.wrench.tail<3>();
    out.push_back(r);
  }
  return out;
}

}  // namespace wysiwyf::robot
