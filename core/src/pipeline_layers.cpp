// The parser's layers: a file and the files it includes (include:), then each --set path=value.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pipeline_parser.hpp"
#include "yaml_delimiters.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/search_paths.hpp"
#include "wysiwyf/validator.hpp"

namespace fs = std::filesystem;

namespace wysiwyf::detail {

// "the '{' opened here is never closed", or closed by the other kind of bracket.
static std::string describe(const UnclosedDelimiter& d) {
  const std::string what = d.open == '"' || d.open == '\'' ? "quote" : "bracket";
  const std::string opened = std::string("the ") + what + " " + d.open + " opened here";
  if (!d.found) return opened + " is never closed";
  return opened + " is closed by a '" + d.found + "' at line " + std::to_string(d.found_line) + ", column " +
         std::to_string(d.found_column) + "; expected '" + (d.open == '[' ? ']' : '}') + "'";
}

void Parser::parse_file(const std::string& path, PipelineSpec& into, const Location& included_from) {
  const std::string canonical = fs::weakly_canonical(path).string();
  if (std::find(stack_.begin(), stack_.end(), canonical) != stack_.end()) {
    error(included_from, "include cycle: '" + path + "' includes itself (through " + join(stack_) + ")");
    return;
  }
  std::ifstream in(path);
  if (!in) {
    std::string why = fs::exists(path) ? "permission denied" : "no such file";
    if (!fs::exists(path) && (!included_from.file.empty() || !fs::path(path).is_absolute())) {
      why += included_from.file.empty()
                 ? " (looked in the working directory, then in each folder of the config path and its pipelines/:"
                 : " (looked beside the including file, then in the config path:";
      for (const auto& d : config_search_dirs()) why += " " + d;
      why += "; $WYSIWYF_CONFIG_PATH adds folders)";
    }
    error(included_from.file.empty() ? Location{path, 0, 0} : included_from,
          "cannot read pipeline file '" + path + "': " + why);
    return;
  }
  std::stringstream text;
  text << in.rdbuf();
  stack_.push_back(canonical);
  parse_text(text.str(), path, into);
  stack_.pop_back();
}

void Parser::parse_text(const std::string& text, const std::string& file, PipelineSpec& into) {
  YAML::Node root;
  const auto unclosed = unclosed_delimiter(text);
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    // At the bracket or quote left open, where one is: that is where the mistake is.
    const Location noticed{file, e.mark.line + 1, e.mark.column + 1};
    if (unclosed)
      error(Location{file, unclosed->line, unclosed->column},
            "YAML syntax error: " + describe(*unclosed) + " (YAML noticed at " + noticed.str() + ": " + e.msg + ")");
    else
      error(noticed, "YAML syntax error: " + e.msg);
    return;
  }
  if (unclosed && (unclosed->open == '"' || unclosed->open == '\'')) {  // (yaml-cpp takes the rest as its text)
    error(Location{file, unclosed->line, unclosed->column}, "YAML syntax error: " + describe(*unclosed));
    return;
  }
  if (!root.IsMap()) {
    error(Location{file, 1, 1},
          "found " + describe_node(root) + " at the top of the file; expected a map with keys " + join(kTopKeys));
    return;
  }
  check_keys(root, file, kTopKeys, "top-level key");
  // Each file states the format it is written in.
  if (const YAML::Node v = root["wysiwyf"]) {
    int version = 0;
    if (!to_int(v, version) || version != kPipelineFormatVersion)
      error(at(v, file), "format version: found " + describe_node(v) + "; expected wysiwyf: " +
                             std::to_string(kPipelineFormatVersion) + " (the version this build reads)");
    else
      into.version.assign(version, at(v, file));
  } else {
    error(Location{file, 1, 1}, "missing 'wysiwyf: " + std::to_string(kPipelineFormatVersion) +
                                    "' (the pipeline format version) at the top of the file");
  }
  if (const YAML::Node inc = root["include"]) {
    std::vector<YAML::Node> items;
    if (inc.IsScalar())
      items.push_back(inc);
    else if (inc.IsSequence())
      for (const auto& i : inc) items.push_back(i);
    else
      error(at(inc, file), "include: found " + describe_node(inc) + "; expected a file name or a list of them");
    for (const auto& item : items) {
      if (!item.IsScalar()) {
        error(at(item, file), "include: found " + describe_node(item) + "; expected a file name");
        continue;
      }
      parse_file(resolve_include(item.Scalar(), file), into, at(item, file));
    }
  }
  apply(root, file, into, /*from_set=*/false);
}

std::string Parser::resolve_include(const std::string& name, const std::string& including) {
  const fs::path p = name;
  if (p.is_absolute()) return name;
  const fs::path beside = fs::path(including).parent_path() / p;
  std::error_code ec;
  if (fs::exists(beside, ec)) return beside.string();
  const std::string found = find_in_config_dirs(name);
  return found.empty() ? beside.string() : found;
}

void Parser::apply_set(const std::string& assignment, PipelineSpec& into) {
  const Location where{"--set " + assignment, 0, 0};
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    error(where, "found '" + assignment + "'; expected --set path=value, e.g. --set tracker.params.threshold=200");
    return;
  }
  std::vector<std::string> path;
  std::stringstream ps(assignment.substr(0, eq));
  for (std::string seg; std::getline(ps, seg, '.');) path.push_back(seg);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception&) {
    value = YAML::Node(assignment.substr(eq + 1));
  }
  if (std::find(kTopKeys.begin(), kTopKeys.end(), path[0]) == kTopKeys.end()) {
    if (!into.find(path[0])) {
      std::vector<std::string> names;
      for (const auto& c : into.components) names.push_back(c.name);
      const std::string near = closest_name(path[0], names);
      error(where, "found component '" + path[0] + "', which the pipeline does not have; expected one of " +
                       join(names) + (near.empty() ? "" : " (did you mean '" + near + "'?)"));
      return;
    }
    path.insert(path.begin(), "components");
  }
  if (path[0] == "include") {
    error(where, "include cannot be set from the command line");
    return;
  }
  YAML::Node root(YAML::NodeType::Map);
  YAML::Node cursor = root;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    cursor[path[i]] = YAML::Node(YAML::NodeType::Map);
    cursor.reset(cursor[path[i]]);  // rebind: operator= would assign into the node
  }
  cursor[path.back()] = value;
  set_location_ = where;
  const std::size_t before = issues.size();
  apply(root, where.file, into, /*from_set=*/true);
  set_location_.reset();
  if (issues.size() > before && path[0] == "components" && path.size() > 1) failed_components.insert(path[1]);
}

}  // namespace wysiwyf::detail
