#include "wysiwyf/context.hpp"

#include <cmath>
#include <iomanip>
#include <limits>

namespace wysiwyf {

Context::Context(Mode mode, const ComponentSpec* spec, detail::TopicBus* bus)
    : mode_(mode), spec_(spec), bus_(bus), instance_(spec ? spec->name : "<describe>") {}

double Context::rate_hz() const { return spec_ && spec_->rate.set ? spec_->rate.value : 0.0; }

std::int64_t Context::period_ns() const {
  const double r = rate_hz();
  return r > 0 ? static_cast<std::int64_t>(std::llround(1e9 / r)) : 0;
}

const Sourced<YAML::Node>* Context::lookup_param(const std::string& name) const {
  if (!spec_ || mode_ == Mode::kDescribe) return nullptr;
  auto it = spec_->params.find(name);
  return it == spec_->params.end() ? nullptr : &it->second;
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

std::string Context::range_text(const Range& r) {
  std::ostringstream s;
  s << "[" << r.min << ", " << r.max << "]";
  return s.str();
}

std::string Context::param_choice(const std::string& name, const std::string& default_value,
                                  const std::string& description, const std::vector<std::string>& choices) {
  declare_param(ParamSpec{name, ParamType::kString, yaml_text(default_value), description, std::nullopt, choices});
  const Sourced<YAML::Node>* given = lookup_param(name);
  if (!given) return default_value;
  std::string value;
  std::string all;
  for (const auto& c : choices) all += (all.empty() ? "" : ", ") + c;
  if (!convert(given->value, value)) {
    add_issue(given->where, param_label(name) + ": found '" + YAML::Dump(given->value) + "'; expected one of " + all);
    return default_value;
  }
  for (const auto& c : choices)
    if (c == value) return value;
  add_issue(given->where, param_label(name) + ": found '" + value + "'; expected one of " + all);
  return default_value;
}

Qos Context::effective_qos(const std::string& port, Qos declared) const {
  if (!spec_) return declared;
  auto it = spec_->qos.find(port);
  return it == spec_->qos.end() ? declared : it->second.apply(declared);
}

std::string Context::topic_for(const std::string& port) const {
  return spec_ ? spec_->topic_for(port) : port;
}

// --- YAML conversions: strict, so "1.5" is not an int and "yes" is not a number. ---

bool Context::convert(const YAML::Node& node, bool& out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  if (s == "true" || s == "True" || s == "TRUE") return out = true, true;
  if (s == "false" || s == "False" || s == "FALSE") return out = false, true;
  return false;
}

bool Context::convert(const YAML::Node& node, std::int64_t& out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  try {
    std::size_t used = 0;
    long long v = std::stoll(s, &used, 0);
    if (used != s.size()) return false;
    out = v;
    return true;
  } catch (...) {
    return false;
  }
}

bool Context::convert(const YAML::Node& node, int& out) {
  std::int64_t v = 0;
  if (!convert(node, v) || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) return false;
  out = static_cast<int>(v);
  return true;
}

bool Context::convert(const YAML::Node& node, double& out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  if (s == ".inf" || s == ".nan" || s == "-.inf") return false;  // no non-finite parameters
  try {
    std::size_t used = 0;
    double v = std::stod(s, &used);
    if (used != s.size() || !std::isfinite(v)) return false;
    out = v;
    return true;
  } catch (...) {
    return false;
  }
}

bool Context::convert(const YAML::Node& node, std::string& out) {
  if (!node.IsScalar()) return false;
  out = node.Scalar();
  return true;
}

bool Context::convert(const YAML::Node& node, std::vector<double>& out) {
  if (!node.IsSequence()) return false;
  out.clear();
  for (const auto& item : node) {
    double v = 0;
    if (!convert(item, v)) return false;
    out.push_back(v);
  }
  return true;
}

bool Context::convert(const YAML::Node& node, std::vector<std::string>& out) {
  if (!node.IsSequence()) return false;
  out.clear();
  for (const auto& item : node) {
    if (!item.IsScalar()) return false;
    out.push_back(item.Scalar());
  }
  return true;
}

std::string Context::yaml_text(bool v) { return v ? "true" : "false"; }
std::string Context::yaml_text(std::int64_t v) { return std::to_string(v); }
std::string Context::yaml_text(double v) {
  std::ostringstream s;
  s << std::setprecision(std::numeric_limits<double>::max_digits10) << v;
  // Shortest text that reads back the same value.
  for (int p = 1; p <= 17; ++p) {
    std::ostringstream t;
    t << std::setprecision(p) << v;
    if (std::stod(t.str()) == v) return t.str();
  }
  return s.str();
}
std::string Context::yaml_text(const std::string& v) { return v.empty() ? "\"\"" : v; }
std::string Context::yaml_text(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + yaml_text(v[i]);
  return s + "]";
}
std::string Context::yaml_text(const std::vector<std::string>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s + "]";
}

}  // namespace wysiwyf
