// What watching costs the loop: config/pipelines/admittance-push.yaml on the real clock (the
// 1 kHz admittance_sim with spin), run again and again with nothing attached and with each
// monitor attached from another process (topic hz, topic echo, record --all, the Foxglove bridge
// with a client subscribed to every topic), the conditions interleaved round by round, in three
// families: the loop's thread as is, pinned to a core of its own, and SCHED_FIFO.
// The monitors take samples in batches (their readers' latency budget, dds::kBatchingPeriod);
// the `_prompt` conditions ask for each sample as it is written (--prompt), as before batching.
// Reports admittance_sim's tick p50/p99 (the kernel's last 1024 ticks: the end of each run,
// long after the monitor attached) as the median over the rounds, and checks that the monitor
// really received samples. `nothing_again` is "nothing" once more, reported against it: the
// noise floor of the ratios in the same run. Rounds: 5, or WYSIWYF_BENCH_ROUNDS.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
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
constexpr const char* kBridgePort = "18203";
const fs::path kWork = fs::path(WYSIWYF_BENCH_WORK_DIR) / "monitor";

// A monitor: the processes that attach it (each a program and its arguments; none: nothing
// attached), and how to tell from the last one's output that it saw the loop's samples.
struct Condition {
  std::string name;
  std::vector<std::vector<std::string>> processes;
  std::string proof;     // text the last process's output must contain
  std::string family{};  // "" (as is), "pinned_" or "fifo_": how the haptic loop's thread runs
};

// How the haptic loop's thread runs, each family measured on its own against its own "nothing":
// as is (a normal thread, anywhere: `priority: ~`); pinned: a normal thread on a core of its own
// (`cpus: [1]`), the rest of the pipeline process (DDS, the publisher thread) and the monitors on
// CPU 0; fifo: SCHED_FIFO (`priority: 80`, as admittance-push.yaml ships it), anywhere, as a
// real-time loop is run (no normal thread preempts its tick).
const std::vector<std::string> kFamilies{"", "pinned_", "fifo_"};
bool pinned(const Condition& c) { return c.family == "pinned_"; }
std::string family_of(const std::string& name) {
  for (const std::string& f : kFamilies)
    if (!f.empty() && name.rfind(f, 0) == 0) return f;
  return "";
}

std::vector<std::string> cli(std::vector<std::string> args) {
  args.insert(args.begin(), WYSIWYF_CLI);
  return args;
}

std::vector<Condition> base_conditions() {
  const std::string domain = std::to_string(kDomain);
  return {
      {"nothing", {}, ""},
      {"nothing_again", {}, ""},
      {"topic_hz", {cli({"topic", "hz", "robot/setpoint", "--domain", domain, "--transport", "local"})}, "rate "},
      {"topic_hz_prompt",
       {cli({"topic", "hz", "robot/setpoint", "--domain", domain, "--transport", "local", "--prompt"})},
       "rate "},
      {"topic_echo",
       {cli({"topic", "echo", "haptics/objects", "--domain", domain, "--transport", "local"})},
       "child_frame_id"},
      {"record_all",
       {cli({"record", "--all", "-o", (kWork / "record.mcap").string(), "--domain", domain, "--transport", "local",
             "--no-progress"})},
       "  haptics/objects: "},
      {"bridge_all",
       {cli({"bridge", "--domain", domain, "--transport", "local", "--port", kBridgePort}),
        {WYSIWYF_FOXGLOVE_SINK, kBridgePort}},
       "received "},
      {"bridge_all_prompt",
       {cli({"bridge", "--domain", domain, "--transport", "local", "--port", kBridgePort, "--prompt"}),
        {WYSIWYF_FOXGLOVE_SINK, kBridgePort}},
       "received "},
  };
}

// Whether a thread of this process may run SCHED_FIFO at the fifo family's priority (root, or
// an rtprio limit): tried on a thread of its own.
bool fifo_allowed() {
  static const bool allowed = [] {
    bool ok = false;
    std::thread probe([&ok] {
      sched_param p{};
      p.sched_priority = 80;
      ok = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p) == 0;
    });
    probe.join();
    if (!ok) std::fprintf(stderr, "bench_monitor: SCHED_FIFO is not allowed here; the fifo_ conditions are left out\n");
    return ok;
  }();
  return allowed;
}

// The conditions of one family; pinned needs a machine of 2 CPUs or more, fifo the right to
// SCHED_FIFO.
std::vector<Condition> conditions(const std::string& family) {
  std::vector<Condition> all;
  if (family == "pinned_" && sysconf(_SC_NPROCESSORS_ONLN) < 2) return all;
  if (family == "fifo_" && !fifo_allowed()) return all;
  for (Condition c : base_conditions()) {
    c.name = family + c.name;
    c.family = family;
    all.push_back(c);
  }
  return all;
}

// This process (and what it starts from now on) on `cpus` only.
void run_on(const std::vector<int>& cpus) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int cpu : cpus) CPU_SET(cpu, &set);
  if (sched_setaffinity(0, sizeof(set), &set) != 0) throw std::runtime_error("sched_setaffinity failed");
}

std::vector<int> all_cpus() {
  std::vector<int> cpus;
  for (long i = 0; i < sysconf(_SC_NPROCESSORS_ONLN); ++i) cpus.push_back(static_cast<int>(i));
  return cpus;
}

class Child {
 public:
  Child(std::vector<std::string> argv_s, const fs::path& out) {
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    // SIGINT as by default in the child, whatever this process inherited: a benchmark started in
    // the background of a script ignores SIGINT, and a child without a handler of its own (the
    // Foxglove sink) would then never stop.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    const int spawned = posix_spawn(&pid_, argv[0], &actions, &attributes, argv.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw std::runtime_error("cannot start " + argv_s.front());
  }
  ~Child() {
    kill(pid_, SIGINT);
    int status = 0;
    waitpid(pid_, &status, 0);
  }

 private:
  pid_t pid_ = -1;
};

// The loop's tick, the kernel's last 1024: wall time, and its cost to the loop's own thread (CPU
// time; user-space instructions where this machine counts them, else -1): what a monitor in
// another process does to the loop's own work, apart from what it does to the machine's noise.
struct Figures {
  double p50_us = 0, p99_us = 0;
  double cpu_p50_us = 0, cpu_p99_us = 0;
  double instructions_p50 = -1, instructions_p99 = -1;
};

Figures run_once(const Condition& c, int round) {
  Loader loader({WYSIWYF_COMPONENT_DIR});
  std::vector<std::string> sets{"domain=" + std::to_string(kDomain),
                                "dds.transport=local",
                                "clock.mode=real",
                                "clock.pace=null",
                                "clock.step=null",
                                std::string("clock.duration=") + (bench::smoke() ? "1500ms" : "4s")};
  if (pinned(c)) sets.push_back("physics.cpus=1");
  sets.push_back(c.family == "fifo_" ? "physics.priority=80" : "physics.priority=~");
  const PipelineSpec spec = load_pipeline(std::string(WYSIWYF_CONFIG_DIR) + "/pipelines/admittance-push.yaml", sets);
  const ValidationResult v = validate_pipeline(spec, loader);
  if (!v.errors.empty()) throw std::runtime_error(v.errors.front().str());
  fs::create_directories(kWork);
  fs::path out;
  if (pinned(c)) run_on({0});  // the monitors started next, and DDS's threads, inherit it
  struct Unpin {
    bool pinned;
    ~Unpin() {
      if (pinned) run_on(all_cpus());
    }
  } unpin{pinned(c)};
  std::vector<std::unique_ptr<Child>> monitor;
  for (std::size_t i = 0; i < c.processes.size(); ++i) {
    out = kWork / (c.name + "-" + std::to_string(round) + "-" + std::to_string(i) + ".txt");
    monitor.push_back(std::make_unique<Child>(c.processes[i], out));
  }
  std::ostringstream log;
  RunOptions options{"", false, &log};
  options.measure_tick_cost = true;
  Runtime runtime(spec, loader, options);
  const RunResult r = runtime.run();
  while (!monitor.empty()) monitor.pop_back();  // the client first, then the bridge
  if (!r.ok) throw std::runtime_error(r.error + "\n" + log.str());
  if (log.str().find("(SCHED_FIFO) refused") != std::string::npos)
    throw std::runtime_error(c.name + ": the loop could not run SCHED_FIFO here:\n" + log.str());
  if (!c.proof.empty()) {
    std::ifstream in(out);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find(c.proof) == std::string::npos)
      throw std::runtime_error(c.name + " saw no samples of the loop; its output:\n" + text.substr(0, 2000));
  }
  for (const auto& comp : r.components)
    if (comp.name == "physics")
      return Figures{comp.tick_p50_us, comp.tick_p99_us,      comp.cpu_p50_us,
                     comp.cpu_p99_us,  comp.instructions_p50, comp.instructions_p99};
  throw std::runtime_error("no 'physics' component in the run");
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

int rounds() {
  if (bench::smoke()) return 1;
  const char* n = std::getenv("WYSIWYF_BENCH_ROUNDS");
  return n && std::atoi(n) > 0 ? std::atoi(n) : 5;
}

// A family's conditions, interleaved round by round, each round starting one condition further
// on (no condition always first after the pause between rounds); measured once, when the
// family's first benchmark runs (so a filter can run one family alone).
const std::map<std::string, std::vector<Figures>>& measurements(const std::string& family) {
  static std::map<std::string, std::map<std::string, std::vector<Figures>>> by_family;
  if (const auto done = by_family.find(family); done != by_family.end()) return done->second;
  std::map<std::string, std::vector<Figures>> m;
  const std::vector<Condition> all = conditions(family);
  for (int round = 0; round < rounds(); ++round)
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Condition& c = all[(i + static_cast<std::size_t>(round)) % all.size()];
      m[c.name].push_back(run_once(c, round));
    }
  return by_family[family] = std::move(m);
}

void TickWithMonitor(benchmark::State& state, const std::string& name) {
  try {
    const std::string family = family_of(name);
    const auto& m = measurements(family);
    std::vector<double> p50, p99, base50, base99;
    for (const auto& f : m.at(name)) p50.push_back(f.p50_us), p99.push_back(f.p99_us);
    const std::string base = family + "nothing";
    for (const auto& f : m.at(base)) base50.push_back(f.p50_us), base99.push_back(f.p99_us);
    for (auto _ : state) benchmark::DoNotOptimize(p50.data());
    state.counters["p50_us"] = median(p50);
    state.counters["p99_us"] = median(p99);
    state.counters["p50_vs_nothing"] = median(p50) / median(base50);
    state.counters["p99_vs_nothing"] = median(p99) / median(base99);
    // Each round against the "nothing" of the same round, the median of those: steadier where
    // the machine drifts over the run (rounds are minutes apart, conditions of a round seconds).
    std::vector<double> paired50, paired99;
    for (std::size_t r = 0; r < p50.size() && r < base50.size(); ++r) {
      paired50.push_back(p50[r] / base50[r]);
      paired99.push_back(p99[r] / base99[r]);
    }
    state.counters["p50_vs_nothing_paired"] = median(paired50);
    state.counters["p99_vs_nothing_paired"] = median(paired99);
    state.counters["rounds"] = static_cast<double>(p50.size());
    // The same, of the tick's cost to the loop's thread (CPU time, instructions where counted).
    const auto cost = [&](const char* key, double Figures::*field) {
      std::vector<double> v, paired;
      const auto& runs = m.at(name);
      const auto& base_runs = m.at(base);
      for (std::size_t r = 0; r < runs.size(); ++r) {
        if (runs[r].*field < 0) return;
        v.push_back(runs[r].*field);
        if (r < base_runs.size() && base_runs[r].*field > 0) paired.push_back(runs[r].*field / base_runs[r].*field);
      }
      state.counters[std::string(key)] = median(v);
      state.counters[std::string(key) + "_vs_nothing_paired"] = median(paired);
    };
    cost("cpu_p50_us", &Figures::cpu_p50_us);
    cost("cpu_p99_us", &Figures::cpu_p99_us);
    cost("instructions_p50", &Figures::instructions_p50);
    cost("instructions_p99", &Figures::instructions_p99);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

// The recorder's throughput: `record --all` on the whole demo (demo-sim.yaml: 42 topics, a dozen
// 640x480 image topics at 25 Hz among them), every sample kept or the benchmark fails.
void RecordDemo(benchmark::State& state) {
  try {
    const fs::path file = kWork / "demo.mcap", out = kWork / "record-demo.txt";
    Loader loader({WYSIWYF_COMPONENT_DIR});
    const PipelineSpec spec =
        load_pipeline(std::string(WYSIWYF_CONFIG_DIR) + "/pipelines/demo-sim.yaml",
                      {"domain=" + std::to_string(kDomain + 1), "record.params.path=" + (kWork / "demo.mp4").string(),
                       "metrics.params.summary=" + (kWork / "demo-metrics.json").string(), "clock.pace=0",
                       std::string("clock.duration=") + (bench::smoke() ? "1s" : "12s")});
    const ValidationResult v = validate_pipeline(spec, loader);
    if (!v.errors.empty()) throw std::runtime_error(v.errors.front().str());
    fs::create_directories(kWork);
    double seconds = 0;
    {
      Child recorder(
          cli({"record", "--all", "-o", file.string(), "--domain", std::to_string(kDomain + 1), "--no-progress"}), out);
      std::ostringstream log;
      RunOptions options{"", false, &log};
      options.start_after_s = 2;  // the recorder matched before t = 0
      Runtime runtime(spec, loader, options);
      const auto start = std::chrono::steady_clock::now();
      const RunResult r = runtime.run();
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - 2;
      std::this_thread::sleep_for(std::chrono::seconds(2));  // the last samples reach the file
      if (!r.ok) throw std::runtime_error(r.error + "\n" + log.str());
    }
    std::ifstream in(out);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    unsigned long long messages = 0, topics = 0, chunks = 0, bytes = 0, lost = 0, overflowed = 0;
    const auto summary = text.find("recorded ");
    if (summary == std::string::npos ||
        std::sscanf(text.c_str() + summary,
                    "recorded %llu messages on %llu topic(s), %llu chunks, %llu bytes into %*s lost %llu before the "
                    "recorder, %llu in it",
                    &messages, &topics, &chunks, &bytes, &lost, &overflowed) != 6)
      throw std::runtime_error("cannot read the recorder's summary:\n" + text);
    fs::remove(file);
    if (lost + overflowed > 0) throw std::runtime_error("the recorder lost samples:\n" + text);
    for (auto _ : state) benchmark::DoNotOptimize(messages);
    state.counters["messages"] = static_cast<double>(messages);
    state.counters["topics"] = static_cast<double>(topics);
    state.counters["MB_per_s"] = static_cast<double>(bytes) / 1e6 / seconds;
    state.counters["messages_per_s"] = static_cast<double>(messages) / seconds;
    state.counters["lost"] = static_cast<double>(lost + overflowed);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

const bool registered = [] {
  for (const std::string& family : kFamilies)
    for (const auto& c : conditions(family))
      benchmark::RegisterBenchmark(("AdmittanceTick/" + c.name).c_str(), TickWithMonitor, c.name)->Iterations(1);
  benchmark::RegisterBenchmark("RecordDemo/all_topics", RecordDemo)->Iterations(1)->Unit(benchmark::kSecond);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
