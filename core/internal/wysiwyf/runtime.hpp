#pragma once
// Runs one process group of a validated pipeline: loads and configures its components, connects
// their ports locally and over DDS, then ticks them on the pipeline's clock until the duration
// ends, a component asks to stop, another component throws, or SIGINT/SIGTERM arrives.
#include <atomic>
#include <functional>
#include <cstdint>
#include <iosfwd>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"

namespace wysiwyf {

struct ComponentReport {
  std::string name;
  std::string type;
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;
  double tick_p50_us = 0;  // the last 1024 ticks, as in the last Diagnostics
  double tick_p99_us = 0;
  double tick_max_us = 0;
  // Over the whole run: the tick duration's 99th percentile (binned, at most 1 % above) and the
  // longest tick.
  double run_tick_p99_us = 0;
  double run_tick_max_us = 0;
  // Real clock: how late ticks started after their deadlines (0 on the sim clock).
  double late_p50_us = 0;
  double late_p99_us = 0;
  double late_max_us = 0;
  std::uint64_t dropped_samples = 0;   // input samples pushed out unread
  std::uint64_t rejected_samples = 0;  // input samples the component could not use
  std::uint64_t warnings = 0;
  // The worst the component was in during the run: "ok", "holding" or "fault" (as it reported,
  // report_health), or "failed" (a lifecycle call threw); with the first reason for it.
  std::string state = "ok";
  std::string state_reason;
  // RunOptions::measure_tick_cost: the last 1024 ticks' cost to their thread, CPU time and
  // user-space instructions (-1: not measured, or no instruction counter on this machine).
  double cpu_p50_us = -1, cpu_p99_us = -1;
  double instructions_p50 = -1, instructions_p99 = -1;
};

struct RunResult {
  bool ok = true;
  std::string stop_reason;  // "duration reached", "stopped by tracker: ...", "signal", ...
  std::string error;        // set when !ok: which component failed where and why
  std::int64_t sim_time_ns = 0;
  double wall_seconds = 0;
  std::vector<ComponentReport> components;
  // What DDS reported per topic over the run, a line each: QoS mismatches with other processes,
  // samples lost on the way in, samples the publisher thread had no time to send. Empty: none.
  std::vector<std::string> dds_problems;
  // Samples the publisher thread sent to other processes, and its wakes that sent any: about one
  // a tick for a reader that wants each sample as it is written, one per dds::kBatchingPeriod on
  // the real clock where every reader declared that latency budget (the monitoring tools).
  std::uint64_t dds_samples_sent = 0, dds_publisher_wakes = 0;
  // With a feed: samples handed to local readers, and those refused (a topic the run publishes
  // itself or nobody reads, or bytes that do not deserialise as the topic's type), per topic.
  std::uint64_t fed_samples = 0;
  std::map<std::string, std::string> feed_refused;  // topic -> why
  // A component that held, faulted or failed during the run (nullptr: none); `wysiwyf run` exits
  // non-zero with it.
  const ComponentReport* first_unhealthy() const {
    for (const auto& c : components)
      if (c.state != "ok") return &c;
    return nullptr;
  }
};

// Recorded samples played into a run (`wysiwyf play --into`): on the sim clock, at the start of
// every step, the kernel asks for the samples due by then and hands each to the local readers of
// its topic as if it had come over DDS (so data-triggered components tick on it in that step).
// A topic that a component of the run publishes itself is not fed.
class SampleFeed {
 public:
  // A sample as DDS carries it: CDR with its 4-byte encapsulation header.
  using Deliver = std::function<void(const std::string& topic, const std::uint8_t* cdr, std::size_t size)>;
  virtual ~SampleFeed() = default;
  virtual void due(std::int64_t t_ns, const Deliver& deliver) = 0;
};

struct RunOptions {
  std::string process;          // empty: every enabled component of the pipeline
  bool progress = false;        // sim clock: a progress line on stderr
  std::ostream* log = nullptr;  // component log lines and lifecycle messages (null: std::cerr)
  SampleFeed* feed = nullptr;   // sim clock: recorded samples to play in (must outlive run())
  // Wall-clock seconds to wait after DDS is up and the components are active, before t = 0: a
  // recorder or monitor in another process is matched by then and misses no sample.
  double start_after_s = 0;
  // Topics that take one writer somewhere in the pipeline (ValidationResult::one_writer_topics):
  // this process's DDS endpoints on them are exclusive even where no local port says so (a
  // monitor reading the robot's setpoint in another group than the arm and the supervisor).
  std::set<std::string> one_writer_topics{};
  // ValidationResult::one_writer_participants: this process's DDS readers of those topics take
  // samples only from that participant (a foreign writer never drives the arm, before or after
  // the display's process is lost).
  std::map<std::string, std::string> one_writer_participants{};
  // ValidationResult::unconnected_topics: no DDS endpoint for them in this process.
  std::set<std::string> unconnected_topics{};
  // Each tick's cost to its thread as well as its wall time (ComponentReport::cpu_p50_us ...): two
  // clock reads and two counter reads more a tick, so off unless asked for (benchmarks).
  bool measure_tick_cost = false;
};

class Runtime {
 public:
  // Keeps its own copy of the spec; the loader must outlive the runtime.
  Runtime(PipelineSpec spec, Loader& loader, RunOptions options = {});
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  RunResult run();
  // Thread-safe and async-signal-free: asks the executor to stop after the current step.
  void request_stop(const std::string& reason);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Routes SIGINT and SIGTERM to a stop request of every Runtime that runs in this process.
void install_stop_signal_handlers();
// True once SIGINT or SIGTERM was received (after install_stop_signal_handlers()).
bool stop_signal_received();

}  // namespace wysiwyf
