#include "wysiwyf/context.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <sstream>

#include "wysiwyf/number_text.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "yaml_scalar.hpp"

namespace wysiwyf {

namespace {

// --- YAML -> parameter values, by the kernel's one set of scalar rules (yaml_scalar.hpp). ---

bool convert(const YAML::Node& node, bool& out) { return detail::scalar_to_bool(node, out); }
bool convert(const YAML::Node& node, std::int64_t& out) { return detail::scalar_to_int64(node, out); }
bool convert(const YAML::Node& node, int& out) { return detail::scalar_to_int(node, out); }
bool convert(const YAML::Node& node, double& out) { return detail::scalar_to_double(node, out); }
bool convert(const YAML::Node& node, std::string& out) {
  if (!node.IsScalar()) return false;
  out = node.Scalar();
  return true;
}
template <class V>
bool convert(const YAML::Node& node, std::vector<V>& out) {
  if (!node.IsSequence()) return false;
  out.clear();
  for (const auto& item : node) {
    V v{};
    if (!convert(item, v)) return false;
    out.push_back(std::move(v));
  }
  return true;
}

// --- parameter values -> YAML text (defaults, for describe) ---

std::string yaml_text(bool v) { return v ? "true" : "false"; }
std::string yaml_text(std::int64_t v) { return std::to_string(v); }
std::string yaml_text(int v) { return std::to_string(v); }
std::string yaml_text(double v) { return round_trip_text(v); }
std::string yaml_text(const std::string& v) { return v.empty() ? "\"\"" : v; }
template <class V>
std::string yaml_text(const std::vector<V>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + yaml_text(v[i]);
  return s + "]";
}

bool in_range(bool, const Range&) { return true; }
bool in_range(std::int64_t v, const Range& r) { return v >= r.min && v <= r.max; }
bool in_range(int v, const Range& r) { return v >= r.min && v <= r.max; }
bool in_range(double v, const Range& r) { return v >= r.min && v <= r.max; }
bool in_range(const std::string&, const Range&) { return true; }
bool in_range(const std::vector<double>& v, const Range& r) {
  for (double x : v)
    if (!(x >= r.min && x <= r.max)) return false;
  return true;
}
bool in_range(const std::vector<std::string>&, const Range&) { return true; }

template <class T>
std::optional<std::size_t> length_of(const T&) {
  return std::nullopt;
}
template <class V>
std::optional<std::size_t> length_of(const std::vector<V>& v) {
  return v.size();
}

std::string range_text(const Range& r) {
  std::ostringstream s;
  s << "[" << r.min << ", " << r.max << "]";
  return s.str();
}

}  // namespace

Context::Context(Mode mode, const ComponentSpec* spec, detail::TopicBus* bus)
    : mode_(mode), spec_(spec), bus_(bus), instance_(spec ? spec->name : "<describe>") {}

double Context::rate_hz() const { return spec_ && spec_->rate.set ? spec_->rate.value : 0.0; }

std::int64_t Context::period_ns() const {
  const double r = rate_hz();
  return r > 0 ? static_cast<std::int64_t>(std::llround(1e9 / r)) : 0;
}

template <class T>
bool Context::read_as(const std::string& name, const T& default_value, const std::string& description,
                      std::optional<Range> range, std::optional<Length> length, T& out) {
  declare_param(ParamSpec{name, ParamTypeOf<T>::value, yaml_text(default_value), description, range, {}, length});
  if (!spec_ || mode_ == Mode::kDescribe) return false;
  const auto it = spec_->params.find(name);
  if (it == spec_->params.end()) return false;
  const Sourced<YAML::Node>& given = it->second;
  const auto found = [&] {
    std::string text = YAML::Dump(given.value);
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
  };
  if (!convert(given.value, out)) {
    add_issue(given.where,
              param_label(name) + ": found '" + found() + "'; expected " + to_string(ParamTypeOf<T>::value));
    return false;
  }
  if (range && !in_range(out, *range)) {
    add_issue(given.where, param_label(name) + ": found " + found() + ", outside the range; expected " +
                               (length_of(out) ? "values" : "a value") + " in " + range_text(*range));
    return false;
  }
  if (const auto n = length_of(out); n && length && !length->accepts(*n)) {
    add_issue(given.where, param_label(name) + ": found " + std::to_string(*n) + " values; expected " + length->text());
    return false;
  }
  return true;
}

#define WYSIWYF_CONTEXT_READ(T)                                                                       \
  bool Context::read(const std::string& name, const T& default_value, const std::string& description, \
                     std::optional<Range> range, std::optional<Length> length, T& out) {              \
    return read_as<T>(name, default_value, description, range, length, out);                          \
  }
WYSIWYF_CONTEXT_READ(bool)
WYSIWYF_CONTEXT_READ(int)
WYSIWYF_CONTEXT_READ(std::int64_t)
WYSIWYF_CONTEXT_READ(double)
WYSIWYF_CONTEXT_READ(std::string)
WYSIWYF_CONTEXT_READ(std::vector<double>)
WYSIWYF_CONTEXT_READ(std::vector<std::string>)
#undef WYSIWYF_CONTEXT_READ

std::string Context::param_choice(const std::string& name, const std::string& default_value,
                                  const std::string& description, const std::vector<std::string>& choices) {
  declare_param(ParamSpec{name, ParamType::kString, yaml_text(default_value), description, std::nullopt, choices, {}});
  if (!spec_ || mode_ == Mode::kDescribe) return default_value;
  const auto it = spec_->params.find(name);
  if (it == spec_->params.end()) return default_value;
  std::string value;
  std::string all;
  for (const auto& c : choices) all += (all.empty() ? "" : ", ") + c;
  if (convert(it->second.value, value))
    for (const auto& c : choices)
      if (c == value) return value;
  add_issue(it->second.where,
            param_label(name) + ": found '" + YAML::Dump(it->second.value) + "'; expected one of " + all);
  return default_value;
}

void Context::reject(const std::string& name, const std::string& why) {
  const bool declared = std::any_of(params_.begin(), params_.end(), [&](const ParamSpec& p) { return p.name == name; });
  if (!declared)
    throw std::logic_error("component '" + instance_ + "' rejects parameter '" + name + "', which it did not declare");
  add_issue(param_location(name), param_label(name) + ": " + why);
}

Location Context::param_location(const std::string& name) const {
  if (!spec_) return Location{"<defaults of " + instance_ + ">", 0, 0};
  const auto it = spec_->params.find(name);
  return it != spec_->params.end() ? it->second.where : spec_->where;  // a default: at the component
}

void Context::declare_param(ParamSpec spec) {
  for (const auto& p : params_)
    if (p.name == spec.name)
      throw std::logic_error("component '" + instance_ + "' declares parameter '" + spec.name + "' twice");
  params_.push_back(std::move(spec));
}

void Context::declare_port(PortSpec spec) {
  for (const auto& p : ports_)
    if (p.name == spec.name)
      throw std::logic_error("component '" + instance_ + "' declares port '" + spec.name + "' twice");
  ports_.push_back(std::move(spec));
}

void Context::add_issue(const Location& where, std::string message) {
  issues_.push_back(ConfigIssue{where, std::move(message)});
}

std::string Context::param_label(const std::string& name) const {
  std::string type = spec_ && spec_->type.set ? " (" + spec_->type.value + ")" : "";
  return "parameter '" + name + "' of component '" + instance_ + "'" + type;
}

Qos Context::effective_qos(const std::string& port, Qos declared) const {
  if (!spec_) return declared;
  auto it = spec_->qos.find(port);
  return it == spec_->qos.end() ? declared : it->second.apply(declared);
}

std::string Context::topic_for(const std::string& port) const { return spec_ ? spec_->topic_for(port) : port; }

}  // namespace wysiwyf
