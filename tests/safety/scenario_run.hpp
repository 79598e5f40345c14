#pragma once
// One scenario of the safety campaign: the display loop (loop_run.hpp) on the PUMA 560 with the
// scenario's user and hand tracker, on the sim clock, checked (safety_checks.hpp).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "safety_checks.hpp"
#include "scenario.hpp"

namespace wysiwyf::safety {

struct ScenarioResult {
  Scenario scenario;
  RunFigures figures;
  double sim_s = 0;   // simulated time the run covered
  double wall_s = 0;  // its wall time
  std::string log;    // the pipeline's output (kept for a replay)
};

// The arm the campaign runs: the PUMA 560 of config/robots/puma560.urdf, tip dev (loaded once).
const robot::ArmModel& campaign_arm();

// Runs `scenario` on DDS domain `domain` with its files in `dir`; `planner` adds surface_planner
// parameters (", name: value" entries: a weakened planner for the campaign's own check).
ScenarioResult run_scenario(const Scenario& scenario, int domain, const std::filesystem::path& dir,
                            const std::string& planner = "");

// The result as one JSON object (no log), and back.
nlohmann::json to_json(const ScenarioResult& r);
ScenarioResult result_from_json(const nlohmann::json& j);

}  // namespace wysiwyf::safety
