// Reads pipeline files: YAML syntax, the schema, include: and --set, with a file:line:column for
// every problem. Checks that need the component libraries are in pipeline_validator.cpp.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "wysiwyf/config_files.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/dds_discovery.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/search_paths.hpp"
#include "wysiwyf/validator.hpp"
#include "yaml_scalar.hpp"

namespace fs = std::filesystem;

namespace wysiwyf {

Qos QosOverride::apply(Qos base) const {
  if (reliability.set) base.reliability = reliability.value;
  if (durability.set) base.durability = durability.value;
  if (depth.set) base.depth = depth.value;
  if (deadline_ns.set) base.deadline_ns = deadline_ns.value;
  return base;
}

std::string ComponentSpec::topic_for(const std::string& port) const {
  auto it = topics.find(port);
  return it != topics.end() ? it->second.value : name + "/" + port;
}

const ComponentSpec* PipelineSpec::find(const std::string& instance) const {
  for (const auto& c : components)
    if (c.name == instance) return &c;
  return nullptr;
}

std::vector<std::string> PipelineSpec::processes() const {
  std::vector<std::string> out;
  for (const auto& c : components) {
    if (!c.is_enabled()) continue;
    const std::string p = c.process_name();
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  }
  return out;
}

std::string PipelineSpec::process_label(const std::string& process) const {
  if (!process.empty()) return process;
  const auto groups = processes();
  return groups.size() == 1 ? groups.front() : "all";
}

std::optional<std::int64_t> parse_duration(const std::string& text) {
  static const std::regex re(R"(^\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(ns|us|ms|s|min|h)\s*$)");
  std::smatch m;
  if (text == "0") return 0;
  if (!std::regex_match(text, m, re)) return std::nullopt;
  const double value = std::stod(m[1].str());
  const std::string unit = m[2].str();
  const double scale = unit == "ns"    ? 1
                       : unit == "us"  ? 1e3
                       : unit == "ms"  ? 1e6
                       : unit == "s"   ? 1e9
                       : unit == "min" ? 60e9
                                       : 3600e9;
  const double ns = value * scale;
  if (!std::isfinite(ns) || ns > 9e18) return std::nullopt;
  return static_cast<std::int64_t>(std::llround(ns));
}

namespace {

const std::vector<std::string> kTopKeys = {"wysiwyf", "name", "include",  "domain",
                                           "clock",   "dds",  "security", "components"};
const std::vector<std::string> kSecurityKeys = {"keys", "identities"};
const std::vector<std::string> kClockKeys = {"mode", "step", "duration", "pace"};
const std::vector<std::string> kDdsKeys = {"transport", "profiles", "participant_profile", "discovery_server"};
const std::vector<std::string> kComponentKeys = {"type", "rate",    "process",         "enabled", "spin",   "priority",
                                                 "cpus", "trigger", "trigger_timeout", "params",  "topics", "qos"};
const std::vector<std::string> kQosKeys = {"reliability", "durability", "depth", "deadline"};

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

std::string describe_node(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return "'" + n.Scalar() + "'";
    default: return "an undefined value";
  }
}

class Parser {
 public:
  std::vector<ConfigIssue> issues;

  void parse_file(const std::string& path, PipelineSpec& into, const Location& included_from) {
    const std::string canonical = fs::weakly_canonical(path).string();
    if (std::find(stack_.begin(), stack_.end(), canonical) != stack_.end()) {
      error(included_from, "include cycle: '" + path + "' includes itself (through " + join(stack_) + ")");
      return;
    }
    std::ifstream in(path);
    if (!in) {
      std::string why = fs::exists(path) ? "permission denied" : "no such file";
      if (!included_from.file.empty() && !fs::exists(path)) {
        why += " (looked beside the including file, then in the config path:";
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

  void parse_text(const std::string& text, const std::string& file, PipelineSpec& into) {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
      error(Location{file, e.mark.line + 1, e.mark.column + 1}, "YAML syntax error: " + e.msg);
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

  // An included file: as written if absolute, else beside the including file, else in the
  // config path (a user's pipeline includes a shipped one: pipelines/demo-sim.yaml). Not found:
  // the path beside the file, so that the error names it.
  static std::string resolve_include(const std::string& name, const std::string& including) {
    const fs::path p = name;
    if (p.is_absolute()) return name;
    const fs::path beside = fs::path(including).parent_path() / p;
    std::error_code ec;
    if (fs::exists(beside, ec)) return beside.string();
    const std::string found = find_in_config_dirs(name);
    return found.empty() ? beside.string() : found;
  }

  // A --set path=value: a one-value layer applied over the files.
  void apply_set(const std::string& assignment, PipelineSpec& into) {
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
    apply(root, where.file, into, /*from_set=*/true);
    set_location_.reset();
  }

 private:
  std::vector<std::string> stack_;
  std::optional<Location> set_location_;  // nodes built for --set have no marks of their own

  Location at(const YAML::Node& n, const std::string& file) const {
    if (set_location_) return *set_location_;
    const YAML::Mark m = n.Mark();
    if (m.line < 0) return Location{file, 0, 0};
    return Location{file, m.line + 1, m.column + 1};
  }
  void error(const Location& where, std::string message) { issues.push_back({where, std::move(message)}); }

  // Duplicate keys of a map (yaml-cpp keeps the last one silently).
  void check_duplicates(const YAML::Node& map, const std::string& file) {
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

  // Unknown and duplicate keys of a map.
  void check_keys(const YAML::Node& map, const std::string& file, const std::vector<std::string>& known,
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

  static bool to_int(const YAML::Node& n, int& out) { return detail::scalar_to_int(n, out); }
  static bool to_double(const YAML::Node& n, double& out) { return detail::scalar_to_double(n, out); }

  bool expect_map(const YAML::Node& n, const std::string& file, const std::string& what) {
    if (n.IsMap()) return true;
    error(at(n, file), what + ": found " + describe_node(n) + "; expected a map");
    return false;
  }
  bool get_string(const YAML::Node& n, const std::string& file, const std::string& what, Sourced<std::string>& out) {
    if (!n.IsScalar()) {
      error(at(n, file), what + ": found " + describe_node(n) + "; expected a string");
      return false;
    }
    out.assign(n.Scalar(), at(n, file));
    return true;
  }
  // A file or folder named in `file`: relative to that file's folder (--set values: as given).
  bool get_path(const YAML::Node& n, const std::string& file, const std::string& what, Sourced<std::string>& out) {
    if (!get_string(n, file, what, out)) return false;
    fs::path p = out.value;
    if (p.is_relative() && !set_location_) p = fs::path(file).parent_path() / p;
    out.value = p.string();
    return true;
  }
  void get_duration(const YAML::Node& n, const std::string& file, const std::string& what, bool allow_zero,
                    Sourced<std::int64_t>& out) {
    const auto ns = n.IsScalar() ? parse_duration(n.Scalar()) : std::nullopt;
    if (!ns || *ns < 0 || (!allow_zero && *ns == 0)) {
      error(at(n, file), what + ": found " + describe_node(n) + "; expected a " + (allow_zero ? "" : "positive ") +
                             "duration with a unit, like 1ms, 20 ms or 12s");
      return;
    }
    out.assign(*ns, at(n, file));
  }

  void apply(const YAML::Node& root, const std::string& file, PipelineSpec& into, bool from_set) {
    if (from_set) check_keys(root, file, kTopKeys, "top-level key");
    if (const YAML::Node n = root["name"]) get_string(n, file, "name", into.name);
    if (const YAML::Node n = root["domain"]) {
      int d = -1;
      if (!to_int(n, d) || d < 0 || d > 232)
        error(at(n, file), "domain: found " + describe_node(n) + "; expected a DDS domain id from 0 to 232");
      else
        into.domain.assign(d, at(n, file));
    }
    if (const YAML::Node n = root["clock"]; n && expect_map(n, file, "clock")) apply_clock(n, file, into.clock);
    if (const YAML::Node n = root["dds"]; n && expect_map(n, file, "dds")) apply_dds(n, file, into.dds);
    if (const YAML::Node n = root["security"]; n && expect_map(n, file, "security"))
      apply_security(n, file, into.security);
    if (const YAML::Node n = root["components"]; n && expect_map(n, file, "components")) {
      for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string name = it->first.Scalar();
        static const std::regex valid_name("^[A-Za-z_][A-Za-z0-9_]*$");
        if (!std::regex_match(name, valid_name)) {
          error(at(it->first, file),
                "component name '" + name + "': expected letters, digits and _ only, not starting with a digit");
          continue;
        }
        if (it->second.IsNull()) {  // `name: ~` in a later file or --set NAME=~ removes the component
          into.components.erase(std::remove_if(into.components.begin(), into.components.end(),
                                               [&](const ComponentSpec& c) { return c.name == name; }),
                                into.components.end());
          continue;
        }
        ComponentSpec* spec = nullptr;
        for (auto& c : into.components)
          if (c.name == name) spec = &c;
        if (!spec) {
          into.components.push_back(ComponentSpec{});
          spec = &into.components.back();
          spec->name = name;
          spec->where = at(it->first, file);
        }
        if (expect_map(it->second, file, "component '" + name + "'")) apply_component(it->second, file, *spec);
      }
      check_duplicates(n, file);
    }
  }

  template <typename Field>
  static void remove_if_null(const YAML::Node& n, const char* key, Field& field) {
    if (const YAML::Node m = n[key]; m && m.IsNull()) field = Field{};
  }

  void apply_clock(const YAML::Node& n, const std::string& file, ClockSpec& clock) {
    check_keys(n, file, kClockKeys, "clock key");
    // `key: ~` removes what an earlier layer set (the clock's default applies): a real-clock
    // variant of a sim pipeline drops its pace and step with `--set clock.pace=null`.
    remove_if_null(n, "mode", clock.mode);
    remove_if_null(n, "step", clock.step_ns);
    remove_if_null(n, "duration", clock.duration_ns);
    remove_if_null(n, "pace", clock.pace);
    if (const YAML::Node m = n["mode"]; m && !m.IsNull()) {
      if (m.IsScalar() && m.Scalar() == "sim")
        clock.mode.assign(ClockMode::kSim, at(m, file));
      else if (m.IsScalar() && m.Scalar() == "real")
        clock.mode.assign(ClockMode::kReal, at(m, file));
      else
        error(at(m, file), "clock mode: found " + describe_node(m) + "; expected sim or real");
    }
    if (const YAML::Node m = n["step"]; m && !m.IsNull()) get_duration(m, file, "clock step", false, clock.step_ns);
    if (const YAML::Node m = n["duration"]; m && !m.IsNull())
      get_duration(m, file, "clock duration", true, clock.duration_ns);
    if (const YAML::Node m = n["pace"]; m && !m.IsNull()) {
      double pace = 0;
      if (!to_double(m, pace) || pace < 0)
        error(at(m, file), "clock pace: found " + describe_node(m) +
                               "; expected a number >= 0 (0: as fast as possible, 1: real time)");
      else
        clock.pace.assign(pace, at(m, file));
    }
  }

  void apply_dds(const YAML::Node& n, const std::string& file, DdsSpec& dds) {
    check_keys(n, file, kDdsKeys, "dds key");
    if (const YAML::Node m = n["transport"]) {
      Sourced<std::string> t;
      if (get_string(m, file, "dds transport", t)) {
        if (std::find(dds::transport_names().begin(), dds::transport_names().end(), t.value) ==
            dds::transport_names().end())
          error(t.where, "dds transport: found '" + t.value + "'; expected one of " + join(dds::transport_names()));
        else
          dds.transport = t;
      }
    }
    if (const YAML::Node m = n["profiles"]) {
      if (get_path(m, file, "dds profiles", dds.profiles_file) && !fs::exists(dds.profiles_file.value))
        error(dds.profiles_file.where, "dds profiles: found '" + dds.profiles_file.value +
                                           "', which does not exist; expected a Fast DDS XML profiles file");
    }
    if (const YAML::Node m = n["participant_profile"])
      get_string(m, file, "dds participant_profile", dds.participant_profile);
    if (const YAML::Node m = n["discovery_server"]) {  // one address or a list of them
      std::vector<std::string> servers;
      const auto add = [&](const YAML::Node& item) {
        if (item.IsScalar() && dds::is_server_address(item.Scalar()))
          servers.push_back(item.Scalar());
        else
          error(at(item, file), "dds discovery_server: found " + describe_node(item) +
                                    "; expected IPv4:port of a discovery server, like 10.0.0.5:11811, or a list");
      };
      if (m.IsSequence())
        for (const auto& item : m) add(item);
      else
        add(m);
      dds.discovery_servers.assign(servers, at(m, file));
    }
  }

  void apply_security(const YAML::Node& n, const std::string& file, SecuritySpec& security) {
    check_keys(n, file, kSecurityKeys, "security key");
    security.where = at(n, file);
    if (const YAML::Node m = n["keys"];
        m && get_path(m, file, "security keys", security.keys) && !fs::is_directory(security.keys.value))
      error(security.keys.where, "security keys: found '" + security.keys.value +
                                     "', which is not a folder; expected the folder scripts/security made");
    if (const YAML::Node m = n["identities"]; m && expect_map(m, file, "security identities")) {
      check_duplicates(m, file);
      for (auto it = m.begin(); it != m.end(); ++it)
        get_string(it->second, file, "security identity of process group '" + it->first.Scalar() + "'",
                   security.identities[it->first.Scalar()]);
    }
  }

  void apply_component(const YAML::Node& n, const std::string& file, ComponentSpec& c) {
    const std::string label = "component '" + c.name + "'";
    check_keys(n, file, kComponentKeys, label + " key");
    if (const YAML::Node m = n["type"]) get_string(m, file, label + " type", c.type);
    if (const YAML::Node m = n["rate"]) {
      double rate = 0;
      if (!to_double(m, rate) || rate <= 0 || rate > 100000)
        error(at(m, file),
              label + " rate: found " + describe_node(m) + "; expected a rate in Hz, above 0 and at most 100000");
      else
        c.rate.assign(rate, at(m, file));
    }
    if (const YAML::Node m = n["process"]) get_string(m, file, label + " process", c.process);
    if (const YAML::Node m = n["enabled"]) {
      if (bool enabled = true; detail::scalar_to_bool(m, enabled))
        c.enabled.assign(enabled, at(m, file));
      else
        error(at(m, file), label + " enabled: found " + describe_node(m) + "; expected true or false");
    }
    // `key: ~` removes what an earlier layer set: `--set physics.priority=~` runs a loop shipped
    // SCHED_FIFO as a normal thread.
    remove_if_null(n, "spin", c.spin_ns);
    remove_if_null(n, "priority", c.priority);
    remove_if_null(n, "cpus", c.cpus);
    remove_if_null(n, "trigger_timeout", c.trigger_timeout_ns);
    if (const YAML::Node m = n["spin"]; m && !m.IsNull()) get_duration(m, file, label + " spin", true, c.spin_ns);
    if (const YAML::Node m = n["priority"]; m && !m.IsNull()) {
      int p = 0;
      if (!to_int(m, p) || p < 1 || p > 99)
        error(at(m, file),
              label + " priority: found " + describe_node(m) + "; expected a SCHED_FIFO priority from 1 to 99");
      else
        c.priority.assign(p, at(m, file));
    }
    if (const YAML::Node m = n["cpus"]; m && !m.IsNull()) {  // one CPU or a list of them
      const std::string expected = "; expected a CPU number (0, 1, ...) or a list of them, e.g. [1] or [2, 3]";
      std::vector<YAML::Node> items;
      if (m.IsSequence())
        for (const auto& item : m) items.push_back(item);
      else
        items.push_back(m);
      std::vector<int> cpus;
      bool ok = !items.empty();
      if (!ok) error(at(m, file), label + " cpus: found an empty list" + expected);
      for (const YAML::Node& cpu : items) {
        int i = -1;
        if (!cpu.IsScalar() || !to_int(cpu, i) || i < 0 || i >= 1024) {
          error(at(cpu, file), label + " cpus: found " + describe_node(cpu) + expected);
          ok = false;
        }
        cpus.push_back(i);
      }
      if (ok) c.cpus.assign(cpus, at(m, file));
    }
    if (const YAML::Node m = n["trigger"]) apply_trigger(m, file, label, c);
    if (const YAML::Node m = n["trigger_timeout"]; m && !m.IsNull())
      get_duration(m, file, label + " trigger_timeout", false, c.trigger_timeout_ns);
    if (const YAML::Node m = n["params"]; m && !m.IsNull() && expect_map(m, file, label + " params")) {
      check_duplicates(m, file);
      for (auto it = m.begin(); it != m.end(); ++it) {
        if (it->second.IsNull()) {  // `key: ~` removes what an earlier layer set: its default applies
          c.params.erase(it->first.Scalar());
          c.param_keys.erase(it->first.Scalar());
          continue;
        }
        c.params[it->first.Scalar()].assign(YAML::Clone(it->second), at(it->second, file));
        c.param_keys[it->first.Scalar()] = at(it->first, file);
      }
    }
    if (const YAML::Node m = n["topics"]; m && !m.IsNull() && expect_map(m, file, label + " topics")) {
      check_duplicates(m, file);
      static const std::regex valid_topic("^[A-Za-z_][A-Za-z0-9_/]*$");
      for (auto it = m.begin(); it != m.end(); ++it) {
        if (it->second.IsNull()) {  // `port: ~` removes what an earlier layer set: the port's default applies
          c.topics.erase(it->first.Scalar());
          c.topic_keys.erase(it->first.Scalar());
          continue;
        }
        Sourced<std::string> topic;
        if (!get_string(it->second, file, label + " topic of port '" + it->first.Scalar() + "'", topic)) continue;
        if (!std::regex_match(topic.value, valid_topic) || topic.value.back() == '/' ||
            topic.value.find("//") != std::string::npos) {
          error(topic.where,
                label + " topic of port '" + it->first.Scalar() + "': found '" + topic.value +
                    "'; expected a name of letters, digits, _ and single / separators, like robot/joint_state");
          continue;
        }
        c.topics[it->first.Scalar()] = topic;
        c.topic_keys[it->first.Scalar()] = at(it->first, file);
      }
    }
    if (const YAML::Node m = n["qos"]; m && !m.IsNull() && expect_map(m, file, label + " qos")) {
      for (auto it = m.begin(); it != m.end(); ++it) {
        const std::string port = it->first.Scalar();
        c.qos_where[port] = at(it->first, file);
        if (expect_map(it->second, file, label + " qos of port '" + port + "'"))
          apply_qos(it->second, file, label + " qos of port '" + port + "'", c.qos[port]);
      }
    }
  }

  // trigger: port, or [port, ...]: the inputs whose samples tick the component.
  void apply_trigger(const YAML::Node& m, const std::string& file, const std::string& label, ComponentSpec& c) {
    std::vector<std::string> ports;
    bool ok = m.IsScalar() || m.IsSequence();
    if (m.IsScalar()) ports.push_back(m.Scalar());
    if (m.IsSequence())
      for (const auto& e : m) {
        if (!e.IsScalar()) ok = false;
        if (e.IsScalar()) ports.push_back(e.Scalar());
      }
    if (!ok || ports.empty() ||
        std::any_of(ports.begin(), ports.end(), [](const std::string& p) { return p.empty(); })) {
      error(at(m, file), label + " trigger: found " + describe_node(m) +
                             "; expected an input port name, or a list of them, whose samples tick the component");
      return;
    }
    c.trigger.assign(ports, at(m, file));
  }

  void apply_qos(const YAML::Node& n, const std::string& file, const std::string& label, QosOverride& q) {
    check_keys(n, file, kQosKeys, "qos key");
    if (const YAML::Node m = n["reliability"]) {
      if (m.IsScalar() && m.Scalar() == "reliable")
        q.reliability.assign(Reliability::kReliable, at(m, file));
      else if (m.IsScalar() && m.Scalar() == "best_effort")
        q.reliability.assign(Reliability::kBestEffort, at(m, file));
      else
        error(at(m, file), label + " reliability: found " + describe_node(m) + "; expected reliable or best_effort");
    }
    if (const YAML::Node m = n["durability"]) {
      if (m.IsScalar() && m.Scalar() == "volatile")
        q.durability.assign(Durability::kVolatile, at(m, file));
      else if (m.IsScalar() && m.Scalar() == "transient_local")
        q.durability.assign(Durability::kTransientLocal, at(m, file));
      else
        error(at(m, file), label + " durability: found " + describe_node(m) + "; expected volatile or transient_local");
    }
    if (const YAML::Node m = n["depth"]) {
      int depth = 0;
      if (!to_int(m, depth) || depth < 1 || depth > 1000)
        error(at(m, file), label + " depth: found " + describe_node(m) + "; expected a whole number from 1 to 1000");
      else
        q.depth.assign(depth, at(m, file));
    }
    if (const YAML::Node m = n["deadline"]) get_duration(m, file, label + " deadline", false, q.deadline_ns);
  }
};

// Checks on the merged pipeline that need no component library.
void check_merged(PipelineSpec& spec, std::vector<ConfigIssue>& issues) {
  const Location top{spec.file, 1, 1};
  if (spec.components.empty())
    issues.push_back({top, "the pipeline has no components; expected a 'components:' map with at least one entry"});
  if (spec.clock_mode() == ClockMode::kReal && spec.clock.pace.set)
    issues.push_back(
        {spec.clock.pace.where, "clock pace: found a pace with the real clock; expected pace only with mode: sim"});
  const std::int64_t step = spec.step_ns();
  for (const auto& c : spec.components) {
    if (!c.type.set)
      issues.push_back({c.where, "component '" + c.name + "' has no type; expected type: <component type>"});
    if (!c.rate.set) {
      issues.push_back({c.where, "component '" + c.name + "' has no rate; expected rate: <ticks per second>"});
      continue;
    }
    const double period = 1e9 / c.rate.value;
    if (c.trigger_timeout_ns.set && !c.is_triggered())
      issues.push_back({c.trigger_timeout_ns.where,
                        "component '" + c.name +
                            "' trigger_timeout: found one without a trigger; expected it with trigger: <input>, "
                            "or no trigger_timeout (the component ticks on its rate)"});
    if (c.spin_ns.set && static_cast<double>(c.spin_ns.value) > period) {
      std::ostringstream msg;
      msg << "component '" << c.name << "' spin: found " << c.spin_ns.value / 1e3 << " us, longer than its period of "
          << period / 1e3 << " us; expected at most the period (typically 50-200 us; the whole period: the thread "
          << "never sleeps between ticks)";
      issues.push_back({c.spin_ns.where, msg.str()});
    }
    if (spec.clock_mode() != ClockMode::kSim) continue;
    const double steps = period / static_cast<double>(step);
    if (std::fabs(steps - std::round(steps)) > 1e-9 * steps || std::round(steps) < 1) {
      std::ostringstream msg;
      msg << "component '" << c.name << "' rate: found " << c.rate.value << " Hz (period " << period / 1e6
          << " ms), which is not a whole number of " << step / 1e6 << " ms sim steps; expected a rate whose period is a"
          << " multiple of the step (at most " << 1e9 / step << " Hz)";
      issues.push_back({c.rate.where, msg.str()});
    }
  }
}

}  // namespace

static PipelineSpec finish(Parser& parser, PipelineSpec spec, const std::vector<std::string>& overrides) {
  if (parser.issues.empty())
    for (const auto& o : overrides) parser.apply_set(o, spec);
  if (parser.issues.empty()) check_merged(spec, parser.issues);
  if (!parser.issues.empty()) throw ConfigError(parser.issues);
  return spec;
}

PipelineSpec load_pipeline(const std::string& file, const std::vector<std::string>& overrides) {
  Parser parser;
  PipelineSpec spec;
  spec.file = file;
  parser.parse_file(file, spec, Location{});
  return finish(parser, std::move(spec), overrides);
}

PipelineSpec load_pipeline_from_string(const std::string& yaml, const std::string& file_name,
                                       const std::vector<std::string>& overrides) {
  Parser parser;
  PipelineSpec spec;
  spec.file = file_name;
  parser.parse_text(yaml, file_name, spec);
  return finish(parser, std::move(spec), overrides);
}

}  // namespace wysiwyf
