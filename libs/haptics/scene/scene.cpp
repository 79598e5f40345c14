#include "scene/scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace wysiwyf::haptics {

namespace {

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& n, const std::string& what) const {
    const YAML::Mark m = n.Mark();
    throw std::runtime_error(file_ + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1) + ": " +
                             what);
  }
  double number(const YAML::Node& n, const std::string& what) const {
    try {
      if (n.IsScalar()) return n.as<double>();
    } catch (const YAML::Exception&) {
    }
    fail(n, what + ": found '" + (n.IsScalar() ? n.Scalar() : std::string("a non-scalar")) + "'; expected a number");
  }
  double positive(const YAML::Node& n, const std::string& what) const {
    const double v = number(n, what);
    if (!(v > 0)) fail(n, what + ": found " + n.Scalar() + "; expected a positive number");
    return v;
  }
  Vec3 vec3(const YAML::Node& n, const std::string& what) const {
    if (!n.IsSequence() || n.size() != 3) fail(n, what + ": expected a list of three numbers");
    return Vec3(number(n[0], what), number(n[1], what), number(n[2], what));
  }
  void keys(const YAML::Node& map, const std::vector<std::string>& known, const std::string& what) const {
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string k = it->first.Scalar();
      if (std::find(known.begin(), known.end(), k) == known.end()) {
        std::string all;
        for (const auto& s : known) all += (all.empty() ? "" : ", ") + s;
        fail(it->first, "unknown " + what + " key '" + k + "'; expected one of " + all);
      }
    }
  }

 private:
  std::string file_;
};

Quat rpy(const Vec3& r) {
  return Quat(Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
              Eigen::AngleAxisd(r.x(), Vec3::UnitX()));
}

bool is_face(const std::string& f) {
  static const std::vector<std::string> faces{"+x", "-x", "+y", "-y", "+z", "-z"};
  return std::find(faces.begin(), faces.end(), f) != faces.end();
}

}  // namespace

Eigen::Isometry3d face_frame(const std::string& face, const Vec3& half) {
  const int axis = face[1] == 'x' ? 0 : face[1] == 'y' ? 1 : 2;
  const double sign = face[0] == '+' ? 1.0 : -1.0;
  Vec3 z = Vec3::Zero();
  z[axis] = sign;
  const Vec3 helper = axis == 2 ? Vec3::UnitX() : Vec3::UnitZ();
  const Vec3 y = z.cross(helper).normalized();
  const Vec3 x = y.cross(z);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = y;
  T.linear().col(2) = z;
  T.translation() = sign * half[axis] * Vec3::Unit(axis);
  return T;
}

namespace {

DisplayFeature parse_feature(const std::string& name, const YAML::Node& f, const Scene& s, const Reader& r) {
  const std::string what = "feature '" + name + "'";
  if (!f.IsMap()) r.fail(f, what + ": expected a map with body, face, kind");
  r.keys(f, {"body", "face", "kind", "at", "edge", "knob_radius"}, what);
  DisplayFeature d;
  d.name = name;
  if (!f["body"]) r.fail(f, what + ": expected body: <a dynamic body>");
  d.body = s.body_index(f["body"].Scalar());
  if (d.body < 0 || !s.models[d.body].dynamic)
    r.fail(f["body"], what + " body: found '" + f["body"].Scalar() + "'; expected a dynamic body of this scene");
  if (!f["face"] || !is_face(f["face"].Scalar()))
    r.fail(f["face"] ? f["face"] : f, what + ": expected face: +x -x +y -y +z or -z");
  d.face = f["face"].Scalar();
  const std::string kind = f["kind"] ? f["kind"].Scalar() : "face";
  if (kind == "face")
    d.kind = DisplayFeature::Kind::kFace;
  else if (kind == "edge")
    d.kind = DisplayFeature::Kind::kEdge;
  else if (kind == "knob")
    d.kind = DisplayFeature::Kind::kKnob;
  else
    r.fail(f["kind"], what + " kind: found '" + kind + "'; expected face, edge or knob");
  const Vec3& half = s.models[d.body].half_extents;
  const Eigen::Isometry3d obj_T_face = face_frame(d.face, half);
  // The face's half sizes along its frame's x and y.
  const Vec3 face_half = (obj_T_face.linear().transpose() * half).cwiseAbs();
  d.touch_u = obj_T_face.linear().col(0), d.touch_v = obj_T_face.linear().col(1), d.normal = obj_T_face.linear().col(2);
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  if (f["at"]) {
    const YAML::Node a = f["at"];
    if (!a.IsSequence() || a.size() != 2) r.fail(a, what + " at: expected [u, v], m in the face's plane");
    at = Eigen::Vector2d(r.number(a[0], what + " at"), r.number(a[1], what + " at"));
    if (std::abs(at.x()) > face_half.x() || std::abs(at.y()) > face_half.y()) r.fail(a, what + " at: outside the face");
  }
  Eigen::Isometry3d face_T_plate = Eigen::Isometry3d::Identity();
  switch (d.kind) {
    case DisplayFeature::Kind::kFace:
      d.touch = obj_T_face * Vec3(at.x(), at.y(), 0);
      d.half_u = face_half.x(), d.half_v = face_half.y();
      face_T_plate.translation() = Vec3(at.x(), at.y(), 0);
      break;
    case DisplayFeature::Kind::kKnob:
      d.knob_radius = f["knob_radius"] ? r.positive(f["knob_radius"], what + " knob_radius") : 0.015;
      face_T_plate.translation() = Vec3(at.x(), at.y(), 0);  // the plate's knob on the virtual one
      d.touch = obj_T_face * (face_T_plate * s.device.knob_offset);
      break;
    case DisplayFeature::Kind::kEdge: {
      // `edge`: the face's edge toward that axis (e.g. +z on the +x face); the plate's edge on it.
      if (!f["edge"] || !is_face(f["edge"].Scalar()) || f["edge"].Scalar()[1] == d.face[1])
        r.fail(f["edge"] ? f["edge"] : f,
               what + ": expected edge: the direction of the face's edge (+x ... -z, not the face's own axis)");
      const std::string e = f["edge"].Scalar();
      Vec3 dir_obj = Vec3::Zero();
      dir_obj[e[1] - 'x'] = e[0] == '+' ? 1.0 : -1.0;
      const Vec3 dir = obj_T_face.linear().transpose() * dir_obj;  // in the face frame: +-x or +-y
      const int axis = std::abs(dir.x()) > 0.5 ? 0 : 1;
      const double reach = face_half[axis], plate = s.device.plate_half[axis];
      Vec3 centre = Vec3::Zero();
      centre[axis] = dir[axis] * (reach - plate);  // the plate's edge on the object's edge
      face_T_plate.translation() = centre;
      Vec3 mid = Vec3::Zero();
      mid[axis] = dir[axis] * reach;
      d.touch = obj_T_face * mid;
      (axis == 0 ? d.half_v : d.half_u) = face_half[1 - axis];
      break;
    }
  }
  d.obj_T_plate = obj_T_face * face_T_plate;
  d.face_point = obj_T_face.translation();
  return d;
}

Scene parse(const YAML::Node& root, const Reader& r) {
  Scene s;
  if (!root.IsMap()) r.fail(root, "expected a map with keys scene, name, gravity, bodies, device");
  r.keys(root, {"scene", "name", "gravity", "bodies", "device", "features"}, "scene");
  if (!root["scene"] || root["scene"].Scalar() != "1") r.fail(root, "expected 'scene: 1' (the scene format version)");
  s.name = root["name"] ? root["name"].Scalar() : "scene";
  if (root["gravity"]) s.gravity = r.vec3(root["gravity"], "gravity");
  const YAML::Node bodies = root["bodies"];
  if (!bodies || !bodies.IsMap() || bodies.size() == 0) r.fail(root, "expected 'bodies:' with at least one body");
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    const YAML::Node b = it->second;
    const std::string name = it->first.Scalar();
    if (!b.IsMap()) r.fail(b, "body '" + name + "': expected a map");
    r.keys(b,
           {"static", "size", "mass", "position", "orientation_rpy", "velocity", "angular_velocity", "restitution",
            "friction"},
           "body '" + name + "'");
    BodyModel m;
    m.name = name;
    m.dynamic = !(b["static"] && b["static"].as<bool>());
    if (!b["size"]) r.fail(b, "body '" + name + "': expected size: [x, y, z] (full extents, m)");
    const Vec3 size = r.vec3(b["size"], "body '" + name + "' size");
    if ((size.array() <= 0).any()) r.fail(b["size"], "body '" + name + "' size: expected positive extents");
    m.half_extents = 0.5 * size;
    if (m.dynamic) {
      if (!b["mass"]) r.fail(b, "body '" + name + "': a dynamic body needs mass: <kg>");
      m.mass = r.positive(b["mass"], "body '" + name + "' mass");
      m.inertia_body = BodyModel::box_inertia(m.mass, m.half_extents);
    }
    if (b["restitution"]) {
      m.restitution = r.number(b["restitution"], "body '" + name + "' restitution");
      if (m.restitution < 0 || m.restitution > 1)
        r.fail(b["restitution"], "body '" + name + "' restitution: expected a value in [0, 1]");
    }
    if (b["friction"]) {
      m.friction = r.number(b["friction"], "body '" + name + "' friction");
      if (m.friction < 0 || m.friction > 2)
        r.fail(b["friction"], "body '" + name + "' friction: found " + b["friction"].Scalar() +
                                  "; expected a Coulomb coefficient in [0, 2]");
    }
    BodyState st;
    if (b["position"]) st.x = r.vec3(b["position"], "body '" + name + "' position");
    if (b["orientation_rpy"]) st.q = rpy(r.vec3(b["orientation_rpy"], "body '" + name + "' orientation_rpy"));
    if (b["velocity"]) st.P = m.mass * r.vec3(b["velocity"], "body '" + name + "' velocity");
    if (b["angular_velocity"])
      st.L = st.q.toRotationMatrix() * m.inertia_body * st.q.toRotationMatrix().transpose() *
             r.vec3(b["angular_velocity"], "body '" + name + "' angular_velocity");
    if (!m.dynamic && (b["velocity"] || b["angular_velocity"]))
      r.fail(b, "body '" + name + "': a static body cannot move");
    s.models.push_back(m);
    s.initial.push_back(st);
  }
  if (const YAML::Node d = root["device"]) {
    r.keys(d, {"body", "face", "sensor_offset", "knob_offset", "tool_mass", "tool_com", "plate_size"}, "device");
    if (!d["body"]) r.fail(d, "device: expected body: <name of a dynamic body>");
    const std::string body = d["body"].Scalar();
    for (std::size_t i = 0; i < s.models.size(); ++i)
      if (s.models[i].name == body) s.device.body = static_cast<int>(i);
    if (s.device.body < 0 || !s.models[s.device.body].dynamic)
      r.fail(d["body"], "device body: found '" + body + "'; expected the name of a dynamic body of this scene");
    if (d["face"]) {
      s.device.face = d["face"].Scalar();
      static const std::vector<std::string> faces{"+x", "-x", "+y", "-y", "+z", "-z"};
      if (std::find(faces.begin(), faces.end(), s.device.face) == faces.end())
        r.fail(d["face"], "device face: found '" + s.device.face + "'; expected one of +x -x +y -y +z -z");
    }
    s.device.obj_T_dev = face_frame(s.device.face, s.models[s.device.body].half_extents);
    if (d["sensor_offset"]) s.device.dev_T_sensor.translation() = r.vec3(d["sensor_offset"], "device sensor_offset");
    if (d["knob_offset"]) s.device.knob_offset = r.vec3(d["knob_offset"], "device knob_offset");
    if (d["tool_mass"]) {
      s.device.tool_mass = r.number(d["tool_mass"], "device tool_mass");
      if (s.device.tool_mass < 0) r.fail(d["tool_mass"], "device tool_mass: expected a mass >= 0");
    }
    if (d["tool_com"]) s.device.tool_com = r.vec3(d["tool_com"], "device tool_com");
    if (const YAML::Node p = d["plate_size"]) {
      if (!p.IsSequence() || p.size() != 2) r.fail(p, "device plate_size: expected [x, y], m");
      s.device.plate_half =
          0.5 * Eigen::Vector2d(r.positive(p[0], "device plate_size"), r.positive(p[1], "device plate_size"));
    }
  }
  if (const YAML::Node features = root["features"]) {
    if (!features.IsMap()) r.fail(features, "features: expected a map of name: {body, face, kind}");
    for (auto it = features.begin(); it != features.end(); ++it)
      s.features.push_back(parse_feature(it->first.Scalar(), it->second, s, r));
  }
  return s;
}

}  // namespace

int Scene::body_index(const std::string& body) const {
  for (std::size_t i = 0; i < models.size(); ++i)
    if (models[i].name == body) return static_cast<int>(i);
  return -1;
}

const DisplayFeature* Scene::feature(const std::string& feature_name) const {
  for (const auto& f : features)
    if (f.name == feature_name) return &f;
  return nullptr;
}

double DisplayFeature::distance(const Vec3& p) const {
  const Vec3 d = p - touch;
  const double u = std::clamp(d.dot(touch_u), -half_u, half_u), v = std::clamp(d.dot(touch_v), -half_v, half_v);
  return (d - u * touch_u - v * touch_v).norm();
}

double DisplayFeature::past_edges(const Vec3& p, const Vec3& half_extents) const {
  const double out = (p - face_point).dot(normal);
  Eigen::Index axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  double other = out;
  for (Eigen::Index i = 0; i < 3; ++i)
    if (i != axis) other = std::max(other, std::abs(p[i]) - half_extents[i]);
  return other - out;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scene file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  return load_scene_from_string(text.str(), path);
}

Scene load_scene_from_string(const std::string& yaml, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::ParserException& e) {
    throw std::runtime_error(name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                             ": YAML syntax error: " + e.msg);
  }
  return parse(root, Reader(name));
}

}  // namespace wysiwyf::haptics
