// One field of a YAML sample (yaml_field).
#include "yaml_field.hpp"

#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <vector>

#include "wysiwyf/validator.hpp"

namespace wysiwyf::cli {

namespace {

// "a.b[2].c" -> a, b, 2, c.
std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : path) {
    if (c == '.' || c == '[' || c == ']') {
      if (!part.empty()) parts.push_back(part);
      part.clear();
    } else {
      part += c;
    }
  }
  if (!part.empty()) parts.push_back(part);
  return parts;
}

bool whole_number(const std::string& s, std::size_t& out) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
  out = std::stoul(s);
  return true;
}

}  // namespace

std::string yaml_field(const std::string& yaml, const std::string& path) {
  const std::vector<std::string> parts = split_path(path);
  if (parts.empty())
    throw std::invalid_argument("--field: found '" + path + "'; expected a field such as header.stamp");
  YAML::Node node = YAML::Load(yaml);
  std::string walked;
  for (const std::string& part : parts) {
    const std::string here = walked.empty() ? "the sample" : "'" + walked + "'";
    std::size_t index = 0;
    if (node.IsSequence()) {
      if (!whole_number(part, index) || index >= node.size())
        throw std::invalid_argument("--field " + path + ": " + here + " is a list of " + std::to_string(node.size()) +
                                    "; expected an index from 0 to " +
                                    std::to_string(node.size() == 0 ? 0 : node.size() - 1) + ", found '" + part + "'");
      node.reset(node[index]);
    } else if (node.IsMap()) {
      std::vector<std::string> names;
      for (const auto& kv : node) names.push_back(kv.first.Scalar());
      if (!node[part]) {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        const std::string near = closest_name(part, names);
        throw std::invalid_argument("--field " + path + ": " + here + " has no field '" + part + "'; it has " + known +
                                    (near.empty() ? "" : " (did you mean '" + near + "'?)"));
      }
      node.reset(node[part]);
    } else {
      throw std::invalid_argument("--field " + path + ": " + here + " is a value, with no field '" + part + "'");
    }
    walked += (walked.empty() ? "" : ".") + part;
  }
  if (node.IsScalar()) return node.Scalar() + "\n";
  YAML::Emitter out;
  out << node;
  return std::string(out.c_str()) + "\n";
}

}  // namespace wysiwyf::cli
