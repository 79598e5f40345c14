#include "campaign_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

namespace wysiwyf::safety {

namespace {

using Figure = std::function<double(const ScenarioResult&)>;

struct Distribution {
  const char* key;
  const char* title;
  const char* unit;
  Figure value;
  bool worst_is_high;  // the worst scenario has the highest value (else the lowest)
};

const std::vector<Distribution>& distributions() {
  static const std::vector<Distribution> d = {
      {"worst_approach_excess_mm_s", "Worst approach speed over the allowed one (idle and surface modes)", "mm/s",
       [](const ScenarioResult& r) { return r.figures.worst_approach_excess * 1e3; }, true},
      {"min_link_separation_mm", "Nearest any link (not the tool) came to the hand", "mm",
       [](const ScenarioResult& r) { return r.figures.min_link_separation * 1e3; }, false},
      {"min_separation_mm", "Nearest any part came to the hand in idle and surface modes", "mm",
       [](const ScenarioResult& r) { return r.figures.min_separation * 1e3; }, false},
      {"max_force_n", "Largest force on the hand", "N", [](const ScenarioResult& r) { return r.figures.max_force; },
       true},
      {"max_joint_speed_percent", "Fastest joint, of its URDF limit", "%",
       [](const ScenarioResult& r) { return r.figures.max_joint_speed_ratio * 100; }, true},
      {"max_switch_step_mm", "Largest setpoint step at a mode switch", "mm",
       [](const ScenarioResult& r) { return r.figures.max_switch_step * 1e3; }, true},
  };
  return d;
}

// Four significant digits, as a reader takes them in.
std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

struct Histogram {
  double lo = 0, width = 1;
  std::vector<int> counts;
};

Histogram histogram(const std::vector<double>& values, int bins = 24) {
  Histogram h;
  if (values.empty()) return h;
  const auto [mn, mx] = std::minmax_element(values.begin(), values.end());
  h.lo = *mn;
  h.width = std::max((*mx - *mn) / bins, 1e-9);
  h.counts.assign(bins, 0);
  for (double v : values) ++h.counts[std::min(bins - 1, static_cast<int>((v - h.lo) / h.width))];
  return h;
}

std::string svg(const Histogram& h, const char* unit) {
  std::ostringstream s;
  const int w = 480, ht = 140, n = static_cast<int>(h.counts.size());
  const int top = n ? *std::max_element(h.counts.begin(), h.counts.end()) : 1;
  s << "<svg width='" << w << "' height='" << ht + 20 << "' role='img'>";
  for (int i = 0; i < n; ++i) {
    const double bh = top ? ht * static_cast<double>(h.counts[i]) / top : 0;
    s << "<rect x='" << i * w / n << "' y='" << ht - bh << "' width='" << w / n - 2 << "' height='" << bh
      << "' fill='#4878a8'><title>" << number(h.lo + i * h.width) << " to " << number(h.lo + (i + 1) * h.width) << " "
      << unit << ": " << h.counts[i] << "</title></rect>";
  }
  s << "<text x='0' y='" << ht + 15 << "' font-size='11'>" << number(h.lo) << " " << unit << "</text><text x='"
    << w - 90 << "' y='" << ht + 15 << "' font-size='11'>" << number(h.lo + n * h.width) << " " << unit
    << "</text></svg>";
  return s.str();
}

std::string escape(const std::string& in) {
  std::string out;
  for (char c : in) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

}  // namespace

nlohmann::json campaign_summary(const std::vector<ScenarioResult>& results, const CampaignInfo& info) {
  nlohmann::json j;
  j["command"] = info.command;
  j["planner"] = info.planner;
  j["jobs"] = info.jobs;
  j["wall_s"] = info.wall_s;
  j["scenarios"] = results.size();
  std::map<std::string, int> kinds, violations;
  int with_faults = 0, touches = 0, misses = 0, failing = 0;
  double sim_s = 0;
  for (const auto& r : results) {
    ++kinds[r.scenario.kind];
    with_faults += !r.scenario.faults.empty();
    touches += r.figures.touches, misses += r.figures.misses;
    sim_s += r.sim_s;
    failing += !r.figures.violations.empty();
    for (const auto& v : r.figures.violations) ++violations[v.check];
  }
  j["kinds"] = kinds;
  j["with_hand_faults"] = with_faults;
  j["simulated_s"] = sim_s;
  j["touches"] = touches;
  j["misses"] = misses;
  j["scenarios_with_violations"] = failing;
  j["violations"] = violations;
  for (const auto& d : distributions()) {
    if (results.empty()) break;
    std::vector<double> values;
    for (const auto& r : results) values.push_back(d.value(r));
    std::vector<std::size_t> order(results.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return d.worst_is_high ? values[a] > values[b] : values[a] < values[b];
    });
    nlohmann::json worst = nlohmann::json::array();
    for (std::size_t i = 0; i < std::min<std::size_t>(5, order.size()); ++i)
      worst.push_back({{"seed", results[order[i]].scenario.seed}, {"value", values[order[i]]}});
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    auto at = [&](double q) { return sorted[static_cast<std::size_t>(q * (sorted.size() - 1))]; };
    const Histogram h = histogram(values);
    j["distributions"][d.key] = {{"title", d.title},     {"unit", d.unit},  {"min", sorted.front()},
                                 {"p50", at(0.5)},       {"p99", at(0.99)}, {"max", sorted.back()},
                                 {"worst_seeds", worst}, {"bin_lo", h.lo},  {"bin_width", h.width},
                                 {"counts", h.counts}};
  }
  return j;
}

nlohmann::json write_campaign_report(const std::vector<ScenarioResult>& results, const CampaignInfo& info,
                                     const std::filesystem::path& dir) {
  const nlohmann::json summary = campaign_summary(results, info);
  std::ofstream(dir / "report.json") << summary.dump(2) << "\n";
  std::ofstream html(dir / "index.html");
  html << "<!doctype html><meta charset='utf-8'><title>WYSIWYF safety campaign</title>"
          "<style>body{font:14px sans-serif;margin:2em;max-width:60em}td,th{padding:2px 8px;text-align:left}"
          "code{background:#eee}</style><h1>Safety campaign</h1><p>"
       << summary["scenarios"] << " simulated users (" << escape(summary["kinds"].dump()) << "), "
       << summary["with_hand_faults"] << " with a faulty hand source; "
       << static_cast<int>(summary["simulated_s"].get<double>()) << " s simulated in " << static_cast<int>(info.wall_s)
       << " s on " << info.jobs << " cores. <code>" << escape(info.command) << "</code></p>";
  if (!info.planner.empty()) html << "<p><b>Weakened planner:</b> <code>" << escape(info.planner) << "</code></p>";
  html << "<h2>Violations</h2><p>" << summary["scenarios_with_violations"]
       << " scenarios with a violation: " << escape(summary["violations"].dump())
       << "</p><table><tr><th>seed</th><th>kind</th><th>check</th><th>t</th>"
       << "<th>what</th><th>replay</th></tr>";
  int shown = 0;
  for (const auto& r : results)
    for (const auto& v : r.figures.violations)
      if (shown++ < 50)
        html << "<tr><td>" << r.scenario.seed << "</td><td>" << r.scenario.kind << "</td><td>" << v.check << "</td><td>"
             << v.t << "</td><td>" << escape(v.detail) << "</td><td><code>scripts/safety-campaign --seed "
             << r.scenario.seed << "</code></td></tr>";
  html << "</table>";
  for (const auto& d : distributions()) {
    if (!summary.contains("distributions")) break;
    const auto& s = summary["distributions"][d.key];
    Histogram h;
    h.lo = s["bin_lo"], h.width = s["bin_width"], h.counts = s["counts"].get<std::vector<int>>();
    std::string worst;
    for (const auto& w : s["worst_seeds"])
      worst += (worst.empty() ? "" : ", ") + std::to_string(w["seed"].get<std::uint64_t>()) + " (" +
               number(w["value"].get<double>()) + ")";
    html << "<h2>" << d.title << "</h2><p>min " << number(s["min"]) << ", p50 " << number(s["p50"]) << ", p99 "
         << number(s["p99"]) << ", max " << number(s["max"]) << " " << d.unit << "; worst seeds: " << worst << "</p>"
         << svg(h, d.unit);
  }
  return summary;
}

}  // namespace wysiwyf::safety
