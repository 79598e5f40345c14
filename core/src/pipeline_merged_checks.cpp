// Checks on the merged pipeline (after every include: and --set) that need no component library.
#include <cmath>
#include <sstream>

#include "pipeline_parser.hpp"

namespace wysiwyf::detail {

static void check_component(const PipelineSpec& spec, const ComponentSpec& c, std::int64_t step,
                            std::vector<ConfigIssue>& issues);

void check_merged(PipelineSpec& spec, std::vector<ConfigIssue>& issues, std::set<std::string>& failed) {
  const Location top{spec.file, 1, 1};
  if (spec.components.empty() && issues.empty())
    issues.push_back({top, "the pipeline has no components; expected a 'components:' map with at least one entry"});
  if (spec.clock_mode() == ClockMode::kReal && spec.clock.pace.set)
    issues.push_back(
        {spec.clock.pace.where, "clock pace: found a pace with the real clock; expected pace only with mode: sim"});
  const std::int64_t step = spec.step_ns();
  for (const auto& c : spec.components) {
    if (failed.count(c.name)) continue;  // (its own error said; a missing type or rate may be its knock-on)
    const std::size_t before = issues.size();
    check_component(spec, c, step, issues);
    if (issues.size() > before) failed.insert(c.name);
  }
}

static void check_component(const PipelineSpec& spec, const ComponentSpec& c, std::int64_t step,
                            std::vector<ConfigIssue>& issues) {
  if (!c.type.set)
    issues.push_back({c.where, "component '" + c.name + "' has no type; expected type: <component type>"});
  if (!c.rate.set) {
    issues.push_back({c.where, "component '" + c.name + "' has no rate; expected rate: <ticks per second>"});
    return;
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
  if (spec.clock_mode() != ClockMode::kSim) return;
  const double steps = period / static_cast<double>(step);
  if (std::fabs(steps - std::round(steps)) > 1e-9 * steps || std::round(steps) < 1) {
    std::ostringstream msg;
    msg << "component '" << c.name << "' rate: found " << c.rate.value << " Hz (period " << period / 1e6
        << " ms), which is not a whole number of " << step / 1e6 << " ms sim steps; expected a rate whose period is a"
        << " multiple of the step (at most " << 1e9 / step << " Hz)";
    issues.push_back({c.rate.where, msg.str()});
  }
}

}  // namespace wysiwyf::detail
