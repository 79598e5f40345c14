#include "measurements.hpp"

#include <sstream>

namespace wysiwyf::display {

void Measurements::measure_until(std::int64_t now_ns, const haptics::Scene& scene) {
  if (haptic.attached()) haptic.measure_until(now_ns, poses);
  visual.measure(scene, poses);
  contact_timing.update(latency);
  contact_timing.forget_before(now_ns - poses.history_ns());
  latency.forget_before(now_ns - poses.history_ns());
}

std::vector<std::string> Measurements::end_lines() const {
  std::vector<std::string> lines;
  auto add = [&](const std::string& line) {
    if (!line.empty()) lines.push_back(line);
  };
  add(visual.end_line());
  for (const auto& line : contact_timing.end_lines()) add(line);
  add(latency.end_line());
  add(bleed.end_line());
  for (const auto& line : setpoint_timing.end_lines()) add(line);
  add(haptic.run_line());
  return lines;
}

std::string Measurements::summary_json() const {
  std::ostringstream j;
  j << "{\n  ";
  contacts.write_json(j);
  j << ",\n  ";
  haptic.write_json(j);
  j << ",\n  ";
  visual.write_json(j);
  j << ",\n  ";
  bleed.write_json(j);
  j << ",\n  ";
  setpoint_timing.write_json(j);
  j << ",\n  ";
  latency.write_json(j);
  j << ",\n  ";
  contact_timing.write_json(j);
  j << ",\n  ";
  health.write_json(j);
  j << "\n}\n";
  return j.str();
}

TimeSeriesRow Measurements::time_series_row(double t_s, const haptics::Scene& scene) const {
  TimeSeriesRow r;
  r.t_s = t_s;
  r.force_n = contact_timing.latest_force();
  if (!poses.plate().empty()) r.plate = poses.plate().back().pose.translation();
  for (std::size_t b = 0; b < scene.models.size(); ++b)
    if (scene.models[b].dynamic && !poses.object(b).empty()) {
      r.cube = poses.object(b).back().pose.translation();
      break;
    }
  r.mode = mode;
  r.attached = haptic.attached();
  r.haptic_mm = haptic.latest_mm();
  r.visual_mm = visual.latest_mm();
  return r;
}

}  // namespace wysiwyf::display
