#pragma once
// What a component sees while it configures: its parameters and ports. The same configure() runs
// in three modes: describe (no pipeline: defaults, for `components describe`), validate (the
// pipeline's values are checked, nothing is connected) and run (ports connected to topics).
// configure() must therefore only declare and read: open devices and threads in activate().
#include <yaml-cpp/yaml.h>

#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "wysiwyf/detail/topic_bus.hpp"
#include "wysiwyf/location.hpp"
#include "wysiwyf/params.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/port.hpp"
#include "wysiwyf/time.hpp"

namespace wysiwyf {

class Context {
 public:
  enum class Mode { kDescribe, kValidate, kRun };

  // spec is null in describe mode; bus is non-null only in run mode.
  Context(Mode mode, const ComponentSpec* spec, detail::TopicBus* bus);

  // A parameter of type T (bool, int, int64_t, double, std::string, vector<double>,
  // vector<string>): the pipeline's value, or default_value when the pipeline gives none.
  template <class T>
  T param(const std::string& name, const T& default_value, const std::string& description,
          std::optional<Range> range = std::nullopt);
  // A string parameter that must be one of `choices`.
  std::string param_choice(const std::string& name, const std::string& default_value,
                           const std::string& description, const std::vector<std::string>& choices);

  template <class T>
  Input<T> input(const std::string& port, const std::string& description, Qos qos = Qos::reliable());
  template <class T>
  Output<T> output(const std::string& port, const std::string& description, Qos qos = Qos::reliable());

  // One line saying what the component does, for `wysiwyf components list`.
  void summary(std::string text) { summary_ = std::move(text); }

  Mode mode() const { return mode_; }
  const std::string& instance_name() const { return instance_; }
  double rate_hz() const;  // the rate the pipeline ticks this component at
  std::int64_t period_ns() const;

  // What was declared and what was wrong (read by the kernel after configure).
  const std::vector<ParamSpec>& declared_params() const { return params_; }
  const std::vector<PortSpec>& declared_ports() const { return ports_; }
  const std::string& summary_text() const { return summary_; }
  const std::vector<ConfigIssue>& issues() const { return issues_; }

 private:
  const Sourced<YAML::Node>* lookup_param(const std::string& name) const;
  void declare_param(ParamSpec spec);
  void declare_port(PortSpec spec);
  void add_issue(const Location& where, std::string message);
  std::string param_label(const std::string& name) const;
  Qos effective_qos(const std::string& port, Qos declared) const;
  std::string topic_for(const std::string& port) const;

  static bool convert(const YAML::Node& node, bool& out);
  static bool convert(const YAML::Node& node, std::int64_t& out);
  static bool convert(const YAML::Node& node, int& out);
  static bool convert(const YAML::Node& node, double& out);
  static bool convert(const YAML::Node& node, std::string& out);
  static bool convert(const YAML::Node& node, std::vector<double>& out);
  static bool convert(const YAML::Node& node, std::vector<std::string>& out);
  static std::string yaml_text(bool v);
  static std::string yaml_text(std::int64_t v);
  static std::string yaml_text(int v) { return yaml_text(static_cast<std::int64_t>(v)); }
  static std::string yaml_text(double v);
  static std::string yaml_text(const std::string& v);
  static std::string yaml_text(const std::vector<double>& v);
  static std::string yaml_text(const std::vector<std::string>& v);
  static bool in_range(bool, const Range&) { return true; }
  static bool in_range(std::int64_t v, const Range& r) { return v >= r.min && v <= r.max; }
  static bool in_range(int v, const Range& r) { return v >= r.min && v <= r.max; }
  static bool in_range(double v, const Range& r) { return v >= r.min && v <= r.max; }
  static bool in_range(const std::string&, const Range&) { return true; }
  static bool in_range(const std::vector<double>& v, const Range& r) {
    for (double x : v)
      if (!(x >= r.min && x <= r.max)) return false;
    return true;
  }
  static bool in_range(const std::vector<std::string>&, const Range&) { return true; }
  static std::string range_text(const Range& r);

  Mode mode_;
  const ComponentSpec* spec_;
  detail::TopicBus* bus_;
  std::string instance_;
  std::string summary_;
  std::vector<ParamSpec> params_;
  std::vector<PortSpec> ports_;
  std::vector<ConfigIssue> issues_;
};

template <class T>
T Context::param(const std::string& name, const T& default_value, const std::string& description,
                 std::optional<Range> range) {
  declare_param(ParamSpec{name, ParamTypeOf<T>::value, yaml_text(default_value), description, range, {}});
  const Sourced<YAML::Node>* given = lookup_param(name);
  if (!given) return default_value;
  T value{};
  if (!convert(given->value, value)) {
    add_issue(given->where, param_label(name) + ": found '" + YAML::Dump(given->value) + "'; expected " +
                                to_string(ParamTypeOf<T>::value));
    return default_value;
  }
  if (range && !in_range(value, *range)) {
    add_issue(given->where, param_label(name) + ": found " + YAML::Dump(given->value) +
                                ", outside the range; expected a value in " + range_text(*range));
    return default_value;
  }
  return value;
}

template <class T>
Input<T> Context::input(const std::string& port, const std::string& description, Qos qos) {
  const Qos effective = effective_qos(port, qos);
  declare_port(PortSpec{port, PortDirection::kInput, MessageTraits<T>::type_name(), description, qos});
  if (!bus_) return Input<T>();
  return Input<T>(bus_->channel<T>(topic_for(port), instance_ + "." + port)->add_reader(effective));
}

template <class T>
Output<T> Context::output(const std::string& port, const std::string& description, Qos qos) {
  const Qos effective = effective_qos(port, qos);
  declare_port(PortSpec{port, PortDirection::kOutput, MessageTraits<T>::type_name(), description, qos});
  if (!bus_) return Output<T>();
  auto* channel = bus_->channel<T>(topic_for(port), instance_ + "." + port);
  channel->add_writer(effective);
  return Output<T>(channel);
}

}  // namespace wysiwyf
