#include "wrist_calibration/scene_tool_load.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "scene/scene.hpp"

namespace wysiwyf::robot {

namespace {

std::size_t indent_of(const std::string& line) {
  const std::size_t i = line.find_first_not_of(' ');
  return i == std::string::npos ? line.size() : i;
}

bool blank_or_comment(const std::string& line) {
  const std::size_t i = line.find_first_not_of(" \t");
  return i == std::string::npos || line[i] == '#';
}

// "  key: value   # comment" -> "  key: <value>   # comment" (the comment kept, aligned as it was).
std::string replace_value(const std::string& line, std::size_t indent, const std::string& key,
                          const std::string& value) {
  const std::size_t hash = line.find(" #");
  std::string out = std::string(indent, ' ') + key + ": " + value;
  if (hash != std::string::npos) {
    const std::size_t comment = line.find('#', hash);
    out += std::string(out.size() < hash + 1 ? hash + 1 - out.size() : 1, ' ') + line.substr(comment);
  }
  return out;
}

}  // namespace

std::string with_tool_load(const std::string& scene_text, const std::string& name, double tool_mass,
                           const Eigen::Vector3d& tool_com) {
  if (!std::isfinite(tool_mass) || tool_mass < 0 || !tool_com.allFinite())
    throw std::runtime_error(name + ": a tool mass >= 0 and a finite centre of mass are needed to write it");
  std::vector<std::string> lines;
  std::istringstream in(scene_text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::size_t device = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (l.rfind("device:", 0) == 0) {
      const std::string rest = l.substr(7);
      const std::size_t v = rest.find_first_not_of(" \t");
      if (v != std::string::npos && rest[v] != '#')
        throw std::runtime_error(name + ":" + std::to_string(i + 1) +
                                 ": device: found a flow-style map; expected a block (one key per line) to rewrite");
      device = i;
    }
  }
  if (device == lines.size())
    throw std::runtime_error(name + ": no device: section; expected a scene whose device carries the tool");
  char mass[64], com[128];
  std::snprintf(mass, sizeof mass, "%.6g", tool_mass);
  std::snprintf(com, sizeof com, "[%.6g, %.6g, %.6g]", tool_com.x(), tool_com.y(), tool_com.z());
  std::size_t indent = 0, end = device + 1;
  bool have_mass = false, have_com = false;
  for (; end < lines.size(); ++end) {
    if (blank_or_comment(lines[end])) continue;
    const std::size_t in_by = indent_of(lines[end]);
    if (in_by == 0) break;
    if (indent == 0) indent = in_by;
    if (in_by != indent) continue;
    const std::string key = lines[end].substr(in_by, lines[end].find(':', in_by) - in_by);
    if (key == "tool_mass") lines[end] = replace_value(lines[end], indent, "tool_mass", mass), have_mass = true;
    if (key == "tool_com") lines[end] = replace_value(lines[end], indent, "tool_com", com), have_com = true;
  }
  if (indent == 0) indent = 2;
  std::vector<std::string> added;
  if (!have_mass) added.push_back(std::string(indent, ' ') + "tool_mass: " + mass + "  # kg, wysiwyf calibrate wrist");
  if (!have_com) added.push_back(std::string(indent, ' ') + "tool_com: " + com + "  # sensor frame, m");
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(device) + 1, added.begin(), added.end());
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  haptics::Scene back;
  try {
    back = haptics::load_scene_from_string(out, name);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(e.what()) + " (the scene with the calibrated tool load)");
  }
  if (std::abs(back.device.tool_mass - tool_mass) > 1e-5 * std::max(1.0, tool_mass) ||
      (back.device.tool_com - tool_com).norm() > 1e-5)
    throw std::runtime_error(name + ": the rewritten device does not read back as the calibrated tool load");
  return out;
}

}  // namespace wysiwyf::robot
