// The pipeline spec's own methods (pipeline_spec.hpp): QoS overrides, topics, process groups, durations.
#include <algorithm>
#include <cmath>
#include <regex>

#include "wysiwyf/pipeline_spec.hpp"

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

std::string PipelineSpec::participant_name(const std::string& process) const {
  return (name.set ? name.value : "pipeline") + "/" + (process.empty() ? "all" : process);
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

}  // namespace wysiwyf
