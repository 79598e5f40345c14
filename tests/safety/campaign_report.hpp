#pragma once
// The safety campaign's report: report.json (the summary, the distributions, the worst seeds)
// and index.html (the same as tables and SVG histograms), from every scenario's result.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenario_run.hpp"

namespace wysiwyf::safety {

struct CampaignInfo {
  std::string command;  // how it was run (the report says it)
  std::string planner;  // extra planner parameters ("" for the shipped planner)
  int jobs = 1;
  double wall_s = 0;
};

// The summary and distributions of `results` as JSON.
nlohmann::json campaign_summary(const std::vector<ScenarioResult>& results, const CampaignInfo& info);

// Writes report.json and index.html into `dir`; returns the summary they hold.
nlohmann::json write_campaign_report(const std::vector<ScenarioResult>& results, const CampaignInfo& info,
                                     const std::filesystem::path& dir);

}  // namespace wysiwyf::safety
