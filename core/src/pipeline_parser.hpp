#pragma once
// The pipeline file parser (load_pipeline), a class spread over the files named at each part below.
#include <yaml-cpp/yaml.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "wysiwyf/location.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "yaml_scalar.hpp"

namespace wysiwyf::detail {

// Collects every problem in `issues` rather than stopping at the first.
class Parser {
 public:
  std::vector<ConfigIssue> issues;
  // Components with a problem of their own (their key, a --set of theirs, a merged check): the
  // validator skips them, so that it adds no knock-on errors to the parser's.
  std::set<std::string> failed_components;

  // The layers (pipeline_layers.cpp): a file, the files it includes, a --set.
  void parse_file(const std::string& path, PipelineSpec& into, const Location& included_from);
  void parse_text(const std::string& text, const std::string& file, PipelineSpec& into);
  // An included file: as written if absolute, else beside the including file, else in the
  // config path (a user's pipeline includes a shipped one: pipelines/demo-sim.yaml). Not found:
  // the path beside the file, so that the error names it.
  static std::string resolve_include(const std::string& name, const std::string& including);
  // A --set path=value: a one-value layer applied over the files.
  void apply_set(const std::string& assignment, PipelineSpec& into);

 private:
  static inline const std::vector<std::string> kTopKeys = {"wysiwyf", "name",     "include",  "domain",    "clock",
                                                           "dds",     "security", "insecure", "components"};
  static inline const std::vector<std::string> kSecurityKeys = {"keys", "identities"};
  static inline const std::vector<std::string> kClockKeys = {"mode", "step", "duration", "pace"};
  static inline const std::vector<std::string> kDdsKeys = {"transport", "profiles", "participant_profile",
                                                           "discovery_server"};
  static inline const std::vector<std::string> kComponentKeys = {
      "type",   "rate",   "process", "enabled", "spin", "priority", "cpus", "trigger", "trigger_timeout",
      "params", "topics", "qos",     "override"};
  static inline const std::vector<std::string> kQosKeys = {"reliability", "durability", "depth", "deadline"};

  std::vector<std::string> stack_;
  std::optional<Location> set_location_;  // nodes built for --set have no marks of their own

  // One node (pipeline_nodes.cpp).
  static std::string join(const std::vector<std::string>& items);
  static std::string describe_node(const YAML::Node& n);
  Location at(const YAML::Node& n, const std::string& file) const;
  void error(const Location& where, std::string message);
  // Duplicate keys of a map (yaml-cpp keeps the last one silently).
  void check_duplicates(const YAML::Node& map, const std::string& file);
  // Unknown and duplicate keys of a map.
  void check_keys(const YAML::Node& map, const std::string& file, const std::vector<std::string>& known,
                  const std::string& what);
  static bool to_int(const YAML::Node& n, int& out) { return detail::scalar_to_int(n, out); }
  static bool to_double(const YAML::Node& n, double& out) { return detail::scalar_to_double(n, out); }
  bool expect_map(const YAML::Node& n, const std::string& file, const std::string& what);
  bool get_string(const YAML::Node& n, const std::string& file, const std::string& what, Sourced<std::string>& out);
  // A file or folder named in `file`: relative to that file's folder (--set values: as given).
  bool get_path(const YAML::Node& n, const std::string& file, const std::string& what, Sourced<std::string>& out);
  void get_duration(const YAML::Node& n, const std::string& file, const std::string& what, bool allow_zero,
                    Sourced<std::int64_t>& out);

  // The top-level keys (pipeline_schema.cpp).
  void apply(const YAML::Node& root, const std::string& file, PipelineSpec& into, bool from_set);
  template <typename Field>
  static void remove_if_null(const YAML::Node& n, const char* key, Field& field) {
    if (const YAML::Node m = n[key]; m && m.IsNull()) field = Field{};
  }
  void apply_clock(const YAML::Node& n, const std::string& file, ClockSpec& clock);
  void apply_dds(const YAML::Node& n, const std::string& file, DdsSpec& dds);
  void apply_security(const YAML::Node& n, const std::string& file, SecuritySpec& security);
  // A later file's entry for a component an earlier layer defined: its changes (no type:), or,
  // with a type:, a new definition, which `override: true` must allow (then it replaces the
  // earlier whole and true is returned); otherwise an error naming both places, and false.
  bool redefines(const YAML::Node& key, const YAML::Node& n, const std::string& file, ComponentSpec& earlier);

  // One component (pipeline_schema_component.cpp).
  void apply_component(const YAML::Node& n, const std::string& file, ComponentSpec& c);
  // trigger: port, or [port, ...]: the inputs whose samples tick the component.
  void apply_trigger(const YAML::Node& m, const std::string& file, const std::string& label, ComponentSpec& c);
  void apply_qos(const YAML::Node& n, const std::string& file, const std::string& label, QosOverride& q);
};

// Checks on the merged pipeline that need no component library (pipeline_merged_checks.cpp).
// A component's own problem is added to `failed`; "no components" only where nothing else failed
// (a components: map that did not parse is not also reported empty).
void check_merged(PipelineSpec& spec, std::vector<ConfigIssue>& issues, std::set<std::string>& failed);

}  // namespace wysiwyf::detail
