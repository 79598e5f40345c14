// How the parser reads one YAML node: where it is, what it holds, its keys, and a string, path or duration in it.
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "pipeline_parser.hpp"
#include "wysiwyf/validator.hpp"

namespace fs = std::filesystem;

namespace wysiwyf::detail {

std::string Parser::join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

std::string Parser::describe_node(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return "'" + n.Scalar() + "'";
    default: return "an undefined value";
  }
}

Location Parser::at(const YAML::Node& n, const std::string& file) const {
  if (set_location_) return *set_location_;
  const YAML::Mark m = n.Mark();
  if (m.line < 0) return Location{file, 0, 0};
  return Location{file, m.line + 1, m.column + 1};
}

void Parser::error(const Location& where, std::string message) { issues.push_back({where, std::move(message)}); }

void Parser::check_duplicates(const YAML::Node& map, const std::string& file) {
  std::map<std::string, Location> seen;
  for (auto it = map.begin(); it != map.end(); ++it) {
    const std::string key = it->first.Scalar();
    const Location where = at(it->first, file);
    if (auto prev = seen.find(key); prev != seen.end())
      error(where, "duplicate key '" + key + "' (first at line " + std::to_string(prev->second.line) + ")");
    else
      seen[key] = where;
  }
}

void Parser::check_keys(const YAML::Node& map, const std::string& file, const std::vector<std::string>& known,
                        const std::string& what) {
  check_duplicates(map, file);
  std::set<std::string> reported;
  for (auto it = map.begin(); it != map.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (std::find(known.begin(), known.end(), key) != known.end() || !reported.insert(key).second) continue;
    const std::string near = closest_name(key, known);
    error(at(it->first, file), "unknown " + what + " '" + key + "'; expected one of " + join(known) +
                                   (near.empty() ? "" : " (did you mean '" + near + "'?)"));
  }
}

bool Parser::expect_map(const YAML::Node& n, const std::string& file, const std::string& what) {
  if (n.IsMap()) return true;
  error(at(n, file), what + ": found " + describe_node(n) + "; expected a map");
  return false;
}

bool Parser::get_string(const YAML::Node& n, const std::string& file, const std::string& what,
                        Sourced<std::string>& out) {
  if (!n.IsScalar()) {
    error(at(n, file), what + ": found " + describe_node(n) + "; expected a string");
    return false;
  }
  out.assign(n.Scalar(), at(n, file));
  return true;
}

bool Parser::get_path(const YAML::Node& n, const std::string& file, const std::string& what,
                      Sourced<std::string>& out) {
  if (!get_string(n, file, what, out)) return false;
  fs::path p = out.value;
  if (p.is_relative() && !set_location_) p = fs::path(file).parent_path() / p;
  out.value = p.string();
  return true;
}

void Parser::get_duration(const YAML::Node& n, const std::string& file, const std::string& what, bool allow_zero,
                          Sourced<std::int64_t>& out) {
  const auto ns = n.IsScalar() ? parse_duration(n.Scalar()) : std::nullopt;
  if (!ns || *ns < 0 || (!allow_zero && *ns == 0)) {
    error(at(n, file), what + ": found " + describe_node(n) + "; expected a " + (allow_zero ? "" : "positive ") +
                           "duration with a unit, like 1ms, 20 ms or 12s");
    return;
  }
  out.assign(*ns, at(n, file));
}

}  // namespace wysiwyf::detail
