// The parser's schema of one component: its keys, trigger: and the qos: of its ports.
#include <algorithm>
#include <regex>

#include "pipeline_parser.hpp"

namespace wysiwyf::detail {

void Parser::apply_component(const YAML::Node& n, const std::string& file, ComponentSpec& c) {
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

void Parser::apply_trigger(const YAML::Node& m, const std::string& file, const std::string& label, ComponentSpec& c) {
  std::vector<std::string> ports;
  bool ok = m.IsScalar() || m.IsSequence();
  if (m.IsScalar()) ports.push_back(m.Scalar());
  if (m.IsSequence())
    for (const auto& e : m) {
      if (!e.IsScalar()) ok = false;
      if (e.IsScalar()) ports.push_back(e.Scalar());
    }
  if (!ok || ports.empty() || std::any_of(ports.begin(), ports.end(), [](const std::string& p) { return p.empty(); })) {
    error(at(m, file), label + " trigger: found " + describe_node(m) +
                           "; expected an input port name, or a list of them, whose samples tick the component");
    return;
  }
  c.trigger.assign(ports, at(m, file));
}

void Parser::apply_qos(const YAML::Node& n, const std::string& file, const std::string& label, QosOverride& q) {
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

}  // namespace wysiwyf::detail
