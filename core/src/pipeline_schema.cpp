// The parser's schema of a pipeline's top-level keys: name, domain, clock, dds, security and the components map.
#include <algorithm>
#include <filesystem>
#include <regex>

#include "pipeline_parser.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/dds_discovery.hpp"

namespace fs = std::filesystem;

namespace wysiwyf::detail {

void Parser::apply(const YAML::Node& root, const std::string& file, PipelineSpec& into, bool from_set) {
  if (from_set) check_keys(root, file, kTopKeys, "top-level key");
  if (const YAML::Node n = root["name"]) get_string(n, file, "name", into.name);
  if (const YAML::Node n = root["domain"]) {
    int d = -1;
    if (!to_int(n, d) || d < 0 || d > 232)
      error(at(n, file), "domain: found " + describe_node(n) + "; expected a DDS domain id from 0 to 232");
    else
      into.domain.assign(d, at(n, file));
  }
  if (const YAML::Node n = root["insecure"]) {
    if (bool insecure = false; detail::scalar_to_bool(n, insecure))
      into.insecure.assign(insecure, at(n, file));
    else
      error(at(n, file), "insecure: found " + describe_node(n) +
                             "; expected true (one-writer streams between processes without DDS-Security, "
                             "knowingly) or false");
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
      if (spec && !from_set && !redefines(it->first, it->second, file, *spec)) continue;
      if (!spec) {
        into.components.push_back(ComponentSpec{});
        spec = &into.components.back();
        spec->name = name;
        spec->where = at(it->first, file);
      }
      const std::size_t before = issues.size();
      if (expect_map(it->second, file, "component '" + name + "'")) apply_component(it->second, file, *spec);
      if (issues.size() > before) failed_components.insert(name);
    }
    check_duplicates(n, file);
  }
}

bool Parser::redefines(const YAML::Node& key, const YAML::Node& n, const std::string& file, ComponentSpec& earlier) {
  if (!n.IsMap() || !n["type"]) return true;  // (a later file's changes to some of its keys)
  bool replace = false;
  if (const YAML::Node o = n["override"]; o && !detail::scalar_to_bool(o, replace)) {
    error(at(o, file), "component '" + earlier.name + "' override: found " + describe_node(o) +
                           "; expected true (this definition replaces the earlier one whole) or false");
    failed_components.insert(earlier.name);
    return false;
  }
  if (!replace) {
    error(at(key, file), "component '" + earlier.name + "' is defined again (with a type); it was defined at " +
                             earlier.where.str() + ". Expected either its changes only, without type: (`" +
                             earlier.name + ": {params: {...}}` changes those keys), or `override: true` to replace " +
                             "it whole");
    failed_components.insert(earlier.name);
    return false;
  }
  const std::string name = earlier.name;
  earlier = ComponentSpec{};
  earlier.name = name;
  earlier.where = at(key, file);
  return true;
}

void Parser::apply_clock(const YAML::Node& n, const std::string& file, ClockSpec& clock) {
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

void Parser::apply_dds(const YAML::Node& n, const std::string& file, DdsSpec& dds) {
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

void Parser::apply_security(const YAML::Node& n, const std::string& file, SecuritySpec& security) {
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

}  // namespace wysiwyf::detail
