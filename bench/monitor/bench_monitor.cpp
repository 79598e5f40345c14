// What watching costs the loop: config/pipelines/admittance-push.yaml on the real clock (the
// 1 kHz admittance_sim with spin), run again and again with nothing attached and with each
// monitor attached from another process (topic hz, topic echo, record --all), the conditions interleaved round by round in one run.
// Reports admittance_sim's tick p50/p99 (the kernel's last 1024 ticks: the end of each run,
// long after the monitor attached) as the median over the rounds, and checks that the monitor
// really received samples.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "../common/smoke.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/runtime.hpp"
#include "wysiwyf/validator.hpp"

extern char** environ;

namespace fs = std::filesystem;
using namespace wysiwyf;

namespace {

constexpr int kDomain = 203;
const fs::path kWork = fs::path(WYSIWYF_BENCH_WORK_DIR) / "monitor";

// A monitor: the `wysiwyf` arguments that attach it (empty: nothing attached), and how to tell
// from its output file that it saw the loop's samples.
struct Condition {
  std::string name;
  std::vector<std::string> args;
  std::string proof;  // text its output must contain
};

std::vector<Condition> conditions() {
  const std::string domain = std::to_string(kDomain);
  return {
      {"nothing", {}, ""},
      {"topic_hz", {"topic", "hz", "robot/setpoint", "--domain", domain, "--transport", "local"}, "rate "},
      {"topic_echo",
       {"topic", "echo", "haptics/objects", "--domain", domain, "--transport", "local"},
       "child_frame_id"},
      {"record_all",
       {"record", "--all", "-o", (kWork / "record.mcap").string(), "--domain", domain, "--transport", "local",
        "--no-progress"},
       "  haptics/objects: "},
  };
}

class Child {
 public:
  Child(const std::vector<std::string>& args, const fs::path& out) {
    std::vector<std::string> argv_s{WYSIWYF_CLI};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0)
      throw std::runtime_error(std::string("cannot start ") + WYSIWYF_CLI);
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() {
    kill(pid_, SIGINT);
    int status = 0;
    waitpid(pid_, &status, 0);
  }

 private:
  pid_t pid_ = -1;
};

struct Figures {
  double p50_us = 0, p99_us = 0;
};

Figures run_once(const Condition& c, int round) {
  Loader loader({WYSIWYF_COMPONENT_DIR});
  const PipelineSpec spec =
      load_pipeline(std::string(WYSIWYF_CONFIG_DIR) + "/pipelines/admittance-push.yaml",
                    {"domain=" + std::to_string(kDomain), "dds.transport=local", "clock.mode=real", "clock.pace=null",
                     "clock.step=null", std::string("clock.duration=") + (bench::smoke() ? "1500ms" : "4s")});
  const ValidationResult v = validate_pipeline(spec, loader);
  if (!v.errors.empty()) throw std::runtime_error(v.errors.front().str());
  fs::create_directories(kWork);
  const fs::path out = kWork / (c.name + "-" + std::to_string(round) + ".txt");
  std::unique_ptr<Child> monitor;
  if (!c.args.empty()) monitor = std::make_unique<Child>(c.args, out);
  std::ostringstream log;
  Runtime runtime(spec, loader, RunOptions{"", false, &log});
  const RunResult r = runtime.run();
  monitor.reset();
  if (!r.ok) throw std::runtime_error(r.error + "\n" + log.str());
  if (!c.proof.empty()) {
    std::ifstream in(out);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find(c.proof) == std::string::npos)
      throw std::runtime_error(c.name + " saw no samples of the loop; its output:\n" + text.substr(0, 2000));
  }
  for (const auto& comp : r.components)
    if (comp.name == "physics") return Figures{comp.tick_p50_us, comp.tick_p99_us};
  throw std::runtime_error("no 'physics' component in the run");
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// Every condition, interleaved round by round; measured once for all the benchmarks.
const std::map<std::string, std::vector<Figures>>& measurements() {
  static const std::map<std::string, std::vector<Figures>> all = [] {
    std::map<std::string, std::vector<Figures>> m;
    const int rounds = bench::smoke() ? 1 : 5;
    for (int round = 0; round < rounds; ++round)
      for (const auto& c : conditions()) m[c.name].push_back(run_once(c, round));
    return m;
  }();
  return all;
}

void TickWithMonitor(benchmark::State& state, const std::string& name) {
  try {
    const auto& m = measurements();
    std::vector<double> p50, p99, base50, base99;
    for (const auto& f : m.at(name)) p50.push_back(f.p50_us), p99.push_back(f.p99_us);
    for (const auto& f : m.at("nothing")) base50.push_back(f.p50_us), base99.push_back(f.p99_us);
    for (auto _ : state) benchmark::DoNotOptimize(p50.data());
    state.counters["p50_us"] = median(p50);
    state.counters["p99_us"] = median(p99);
    state.counters["p50_vs_nothing"] = median(p50) / median(base50);
    state.counters["p99_vs_nothing"] = median(p99) / median(base99);
    state.counters["rounds"] = static_cast<double>(p50.size());
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

const bool registered = [] {
  for (const auto& c : conditions())
    benchmark::RegisterBenchmark(("AdmittanceTick/" + c.name).c_str(), TickWithMonitor, c.name)->Iterations(1);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
