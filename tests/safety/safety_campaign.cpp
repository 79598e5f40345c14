// safety_campaign: N simulated users on the display loop (the PUMA 560, the sim clock, no
// rendering), on every core, each checked at every 1 ms sample; writes report.json and
// index.html, and exits 1 when any scenario broke a check. `--seed S` replays one scenario and
// keeps its run's files. Run through scripts/safety-campaign.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>

#include "campaign_report.hpp"

namespace fs = std::filesystem;
using namespace wysiwyf::safety;

namespace {

struct Options {
  long scenarios = 1000;
  std::uint64_t first_seed = 1;
  long jobs = std::max(1u, std::thread::hardware_concurrency());
  int domain = 170;  // the workers use domain .. domain + jobs - 1
  fs::path out = "safety-campaign";
  std::string planner;
  long replay = -1;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "safety_campaign: " << why
            << "\nusage: safety_campaign [--scenarios N] [--first-seed S] [--jobs J] [--domain D] [--out DIR]\n"
               "                       [--planner ', name: value ...'] [--seed S (replay one)]\n";
  std::exit(2);
}

long number(const char* text, long lo, long hi, const char* what) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (!end || *end || v < lo || v > hi)
    usage(std::string(what) + ": " + text + " is not a whole number in [" + std::to_string(lo) + ", " +
          std::to_string(hi) + "]");
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) usage(a + " needs a value");
    const char* v = argv[++i];
    if (a == "--scenarios")
      o.scenarios = number(v, 1, 10'000'000, "--scenarios");
    else if (a == "--first-seed")
      o.first_seed = static_cast<std::uint64_t>(number(v, 0, 1L << 62, "--first-seed"));
    else if (a == "--jobs")
      o.jobs = number(v, 1, 256, "--jobs");
    else if (a == "--domain")
      o.domain = static_cast<int>(number(v, 0, 200, "--domain"));
    else if (a == "--out")
      o.out = v;
    else if (a == "--planner")
      o.planner = v;
    else if (a == "--seed")
      o.replay = number(v, 0, 1L << 62, "--seed");
    else
      usage("unknown option " + a);
  }
  if (o.domain + o.jobs > 232) usage("--domain + --jobs must stay within DDS domain 232");
  return o;
}

void print(const ScenarioResult& r) {
  std::printf(
      "seed %llu (%s%s%s): %.1f s simulated in %.1f s; worst approach %+.1f mm/s over the limit (%s at %.3f s), "
      "nearest link %.1f mm, force %.1f N, %d touched, %d missed, %zu violation(s)\n",
      static_cast<unsigned long long>(r.scenario.seed), r.scenario.kind.c_str(), r.scenario.faults.empty() ? "" : "; ",
      r.scenario.faults.c_str(), r.sim_s, r.wall_s, r.figures.worst_approach_excess * 1e3, r.figures.worst_part.c_str(),
      r.figures.worst_t, r.figures.min_link_separation * 1e3, r.figures.max_force, r.figures.touches, r.figures.misses,
      r.figures.violations.size());
  for (const auto& v : r.figures.violations)
    std::printf("  VIOLATION %s at %.3f s: %s (%.4g against %.4g)\n", v.check.c_str(), v.t, v.detail.c_str(), v.value,
                v.limit);
  std::fflush(stdout);
}

// Worker k: seeds first + k, first + k + jobs, ...; one JSON line each.
int work(const Options& o, long k) {
  std::ofstream out(o.out / ("results-" + std::to_string(k) + ".jsonl"));
  for (long i = k; i < o.scenarios; i += o.jobs) {
    const Scenario s = make_scenario(o.first_seed + static_cast<std::uint64_t>(i));
    const ScenarioResult r =
        run_scenario(s, o.domain + static_cast<int>(k), o.out / ("work-" + std::to_string(k)), o.planner);
    out << to_json(r).dump() << "\n" << std::flush;
    if (!r.figures.violations.empty()) print(r);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  fs::create_directories(o.out);
  std::string command = "safety_campaign";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  if (o.replay >= 0) {
    const Scenario s = make_scenario(static_cast<std::uint64_t>(o.replay));
    const fs::path dir = o.out / ("seed-" + std::to_string(o.replay));
    std::printf("seed %ld: %s\n  tracker: {%s}\n", o.replay, s.kind.c_str(), s.tracker.c_str());
    for (const auto& line : s.script) std::printf("  %s\n", line.c_str());
    const ScenarioResult r = run_scenario(s, o.domain, dir, o.planner);
    std::ofstream(dir / "pipeline.log") << r.log;
    print(r);
    std::printf("the run's samples and events: %s\n", dir.c_str());
    return r.figures.violations.empty() ? 0 : 1;
  }
  const auto start = std::chrono::steady_clock::now();
  // Workers are processes (one DDS domain each), forked before anything opens DDS here.
  std::vector<pid_t> workers;
  for (long k = 0; k < o.jobs; ++k) {
    const pid_t pid = fork();
    if (pid == 0) std::_Exit(work(o, k));
    if (pid < 0) {
      std::perror("fork");
      return 2;
    }
    workers.push_back(pid);
  }
  int failed = 0;
  for (pid_t pid : workers) {
    int status = 0;
    waitpid(pid, &status, 0);
    failed += !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  std::vector<ScenarioResult> results;
  for (long k = 0; k < o.jobs; ++k) {
    std::ifstream in(o.out / ("results-" + std::to_string(k) + ".jsonl"));
    for (std::string line; std::getline(in, line);) results.push_back(result_from_json(nlohmann::json::parse(line)));
  }
  std::sort(results.begin(), results.end(),
            [](const ScenarioResult& a, const ScenarioResult& b) { return a.scenario.seed < b.scenario.seed; });
  CampaignInfo info{command, o.planner, static_cast<int>(o.jobs),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
  const nlohmann::json summary = write_campaign_report(results, info, o.out);
  std::printf("%zu of %ld scenarios ran (%d worker(s) failed); %d with a violation %s; report: %s\n", results.size(),
              o.scenarios, failed, summary["scenarios_with_violations"].get<int>(),
              summary["violations"].dump().c_str(), (o.out / "index.html").c_str());
  if (failed || static_cast<long>(results.size()) != o.scenarios) return 2;
  return summary["scenarios_with_violations"].get<int>() == 0 ? 0 : 1;
}
