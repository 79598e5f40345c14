#include "calibration/flange_views_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace wysiwyf::vision::calibration {

namespace {

[[noreturn]] void fail(const std::string& file, const YAML::Node& n, const std::string& what) {
  const YAML::Mark m = n.Mark();
  throw std::runtime_error(file + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1) + ": " + what);
}

}  // namespace

std::vector<FlangeViewEntry> load_flange_views(const std::string& path, int joints) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(path + ": cannot read the views file");
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                             ": not YAML: " + e.msg);
  }
  if (!root.IsMap() || !root["views"] || !root["views"].IsSequence())
    fail(path, root, "expected a map with views: [{image: FILE, joints: [...]}, ...]");
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it->first.Scalar() != "views")
      fail(path, it->first, "unknown key '" + it->first.Scalar() + "'; expected views");
  const YAML::Node list = root["views"];
  if (list.size() > 1000) fail(path, list, "views: " + std::to_string(list.size()) + " entries; expected at most 1000");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<FlangeViewEntry> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node v = list[i];
    const std::string where = "views[" + std::to_string(i) + "]";
    if (!v.IsMap()) fail(path, v, where + ": expected a map {image, joints}");
    for (auto it = v.begin(); it != v.end(); ++it)
      if (it->first.Scalar() != "image" && it->first.Scalar() != "joints")
        fail(path, it->first, where + ": unknown key '" + it->first.Scalar() + "'; expected image, joints");
    const YAML::Node image = v["image"], q = v["joints"];
    if (!image || !image.IsScalar() || image.Scalar().empty() || image.Scalar().size() > 4096)
      fail(path, image ? image : v, where + " image: expected the path of an image file");
    if (!q || !q.IsSequence() || static_cast<int>(q.size()) != joints)
      fail(path, q ? q : v, where + " joints: expected a list of " + std::to_string(joints) + " numbers");
    FlangeViewEntry e;
    e.label = image.Scalar();
    e.image = (folder / image.Scalar()).string();
    e.joints.resize(joints);
    for (int j = 0; j < joints; ++j) {
      double x = NAN;
      try {
        if (q[j].IsScalar()) x = q[j].as<double>();
      } catch (const YAML::Exception&) {
      }
      if (!std::isfinite(x)) fail(path, q[j], where + " joints: expected finite numbers (rad, m)");
      e.joints[j] = x;
    }
    out.push_back(e);
  }
  return out;
}

}  // namespace wysiwyf::vision::calibration
