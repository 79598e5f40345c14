#include "scenario_run.hpp"

#include <chrono>

namespace wysiwyf::safety {

const robot::ArmModel& campaign_arm() {
  static const robot::ArmModel model(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "dev");
  return model;
}

ScenarioResult run_scenario(const Scenario& scenario, int domain, const std::filesystem::path& dir,
                            const std::string& planner) {
  test::LoopSetup setup;
  setup.script = scenario.script;
  setup.tracker = scenario.tracker;
  setup.planner = planner;
  setup.domain = domain;
  std::vector<std::string> errors;
  const auto start = std::chrono::steady_clock::now();
  test::LoopRun run = test::run_loop_in(setup, dir, &errors);
  ScenarioResult r;
  r.scenario = scenario;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.sim_s = run.ticks.empty() ? 0 : run.ticks.back().t - run.ticks.front().t;
  for (const auto& e : errors) run.result.ok = false, run.result.error += e + "; ";
  r.figures = check_run(run, campaign_arm());
  r.log = std::move(run.log);
  return r;
}

nlohmann::json to_json(const ScenarioResult& r) {
  const RunFigures& f = r.figures;
  nlohmann::json violations = nlohmann::json::array();
  for (const auto& v : f.violations)
    violations.push_back(
        {{"check", v.check}, {"t", v.t}, {"value", v.value}, {"limit", v.limit}, {"detail", v.detail}});
  return {{"seed", r.scenario.seed},
          {"kind", r.scenario.kind},
          {"faults", r.scenario.faults},
          {"script", r.scenario.script},
          {"tracker", r.scenario.tracker},
          {"sim_s", r.sim_s},
          {"wall_s", r.wall_s},
          {"samples", f.samples},
          {"worst_approach_excess", f.worst_approach_excess},
          {"worst_part", f.worst_part},
          {"worst_t", f.worst_t},
          {"min_separation", f.min_separation},
          {"min_link_separation", f.min_link_separation},
          {"max_force", f.max_force},
          {"max_joint_speed_ratio", f.max_joint_speed_ratio},
          {"max_setpoint_speed", f.max_setpoint_speed},
          {"max_switch_step", f.max_switch_step},
          {"touches", f.touches},
          {"misses", f.misses},
          {"switches", f.switches},
          {"violations", violations}};
}

ScenarioResult result_from_json(const nlohmann::json& j) {
  ScenarioResult r;
  r.scenario.seed = j.at("seed").get<std::uint64_t>();
  r.scenario.kind = j.at("kind").get<std::string>();
  r.scenario.faults = j.at("faults").get<std::string>();
  r.scenario.script = j.at("script").get<std::vector<std::string>>();
  r.scenario.tracker = j.at("tracker").get<std::string>();
  r.sim_s = j.at("sim_s").get<double>();
  r.wall_s = j.at("wall_s").get<double>();
  RunFigures& f = r.figures;
  f.samples = j.at("samples").get<int>();
  f.worst_approach_excess = j.at("worst_approach_excess").get<double>();
  f.worst_part = j.at("worst_part").get<std::string>();
  f.worst_t = j.at("worst_t").get<double>();
  f.min_separation = j.at("min_separation").get<double>();
  f.min_link_separation = j.at("min_link_separation").get<double>();
  f.max_force = j.at("max_force").get<double>();
  f.max_joint_speed_ratio = j.at("max_joint_speed_ratio").get<double>();
  f.max_setpoint_speed = j.at("max_setpoint_speed").get<double>();
  f.max_switch_step = j.at("max_switch_step").get<double>();
  f.touches = j.at("touches").get<int>();
  f.misses = j.at("misses").get<int>();
  f.switches = j.at("switches").get<int>();
  for (const auto& v : j.at("violations"))
    f.violations.push_back({v.at("check").get<std::string>(), v.at("t").get<double>(), v.at("value").get<double>(),
                            v.at("limit").get<double>(), v.at("detail").get<std::string>()});
  return r;
}

}  // namespace wysiwyf::safety
