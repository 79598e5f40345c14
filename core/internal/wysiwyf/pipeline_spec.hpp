#pragma once
// The pipeline file as data: what the YAML says, with where each value was written, after
// include: files and --set overrides are merged. Parsing is in pipeline_parser.cpp, checking
// against the component libraries in pipeline_validator.cpp.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "wysiwyf/location.hpp"
#include "wysiwyf/qos.hpp"

namespace wysiwyf {

// A value and where it was written; `set` is false when no file or --set gave it.
template <class T>
struct Sourced {
  T value{};
  Location where;
  bool set = false;
  void assign(T v, Location at) {
    value = std::move(v);
    where = std::move(at);
    set = true;
  }
};

struct QosOverride {
  Sourced<Reliability> reliability;
  Sourced<Durability> durability;
  Sourced<int> depth;
  Sourced<std::int64_t> deadline_ns;
  Qos apply(Qos base) const;
};

struct ComponentSpec {
  std::string name;  // instance name: the key under components:
  Location where;    // of the key
  Sourced<std::string> type;
  Sourced<double> rate;  // Hz
  Sourced<std::string> process;
  Sourced<bool> enabled;
  // Real clock only (ignored on the sim clock, so a pipeline swaps clocks by one line):
  Sourced<std::int64_t> spin_ns;   // wake this long before each tick and busy-wait the rest
  Sourced<int> priority;           // SCHED_FIFO priority of the component's thread, 1..99
  Sourced<std::vector<int>> cpus;  // the CPUs the component's thread may run on (pinned)
  // Input ports whose samples tick the component (data-triggered) instead of its period; the
  // sim clock ticks it in the same step, right after the producer.
  Sourced<std::vector<std::string>> trigger;
  // Data-triggered: also tick when no trigger sample came for this long (a watchdog tick, so a
  // triggered supervisor still notices its inputs falling silent).
  Sourced<std::int64_t> trigger_timeout_ns;
  std::map<std::string, Sourced<YAML::Node>> params;
  std::map<std::string, Sourced<std::string>> topics;  // port -> topic
  std::map<std::string, QosOverride> qos;              // port -> overrides
  std::map<std::string, Location> qos_where;           // port -> where its qos entry is
  std::map<std::string, Location> param_keys;          // parameter -> where its name is written
  std::map<std::string, Location> topic_keys;          // port -> where its name is written

  std::string process_name() const { return process.set ? process.value : "main"; }
  bool is_enabled() const { return !enabled.set || enabled.value; }
  bool is_triggered() const { return trigger.set && !trigger.value.empty(); }
  // The topic a port is mapped to: the pipeline's mapping, or "<instance>/<port>".
  std::string topic_for(const std::string& port) const;
};

enum class ClockMode { kSim, kReal };

struct ClockSpec {
  Sourced<ClockMode> mode;
  Sourced<std::int64_t> step_ns;      // sim: the lockstep increment
  Sourced<std::int64_t> duration_ns;  // 0: until stopped
  Sourced<double> pace;               // sim: 0 as fast as possible, 1 real time, 2 twice real time
};

struct DdsSpec {
  Sourced<std::string> transport;            // dds::transport_names(): "default", "local", ...
  Sourced<std::string> profiles_file;        // Fast DDS XML profiles, relative to the pipeline file
  Sourced<std::string> participant_profile;  // profile name in that file
  // Fast DDS Discovery Servers (IPv4:port, `wysiwyf discovery-server`): participants find each
  // other through them instead of by multicast.
  Sourced<std::vector<std::string>> discovery_servers;
};

// DDS-Security (scripts/security makes the folder): each process group authenticates as the
// identity named for it.
struct SecuritySpec {
  Sourced<std::string> keys;                               // the folder, relative to the pipeline file
  std::map<std::string, Sourced<std::string>> identities;  // process group -> identity
  Location where;                                          // of the `security:` key
  bool enabled() const { return keys.set; }
};

struct PipelineSpec {
  std::string file;  // the top-level file
  Sourced<int> version;
  Sourced<std::string> name;
  Sourced<int> domain;
  ClockSpec clock;
  DdsSpec dds;
  SecuritySpec security;
  // `insecure: true`: the pipeline takes a one-writer stream (the arm's setpoint) from another
  // process without DDS-Security, knowingly (validation refuses it otherwise).
  Sourced<bool> insecure;
  std::vector<ComponentSpec> components;  // in file order (included files first)
  bool accepts_insecure() const { return insecure.set && insecure.value; }

  const ComponentSpec* find(const std::string& instance) const;
  std::vector<std::string> processes() const;  // distinct process groups, in order of appearance
  int domain_id() const { return domain.set ? domain.value : 0; }
  ClockMode clock_mode() const { return clock.mode.set ? clock.mode.value : ClockMode::kSim; }
  std::int64_t step_ns() const { return clock.step_ns.set ? clock.step_ns.value : 1'000'000; }
  std::int64_t duration_ns() const { return clock.duration_ns.set ? clock.duration_ns.value : 0; }
  double pace() const { return clock.pace.set ? clock.pace.value : 0.0; }
  std::string transport() const { return dds.transport.set ? dds.transport.value : "default"; }
  // The process that runs `process` ("" = every group in one process): the group's own name,
  // "main" for a pipeline without groups, "all" for several groups run together.
  std::string process_label(const std::string& process) const;
  // The DDS participant name of the process that runs group `process` ("" the whole pipeline):
  // "<pipeline>/<group>", or "<pipeline>/all"; the runtime appends "/<pid>" on a plain domain.
  std::string participant_name(const std::string& process) const;
};

constexpr int kPipelineFormatVersion = 1;

// Reads a pipeline file and its includes, then applies `--set path=value` overrides in order.
// Throws ConfigError listing every syntax and schema problem with file:line:column.
PipelineSpec load_pipeline(const std::string& file, const std::vector<std::string>& overrides = {});

// The same, for reporting every problem of a file at once: what parsed (a wrong value left at its
// default), every problem found, and the components with problems of their own, which the
// validator should skip (validate_pipeline's `skip`) so that it reports no knock-on of them.
struct ParsedPipeline {
  PipelineSpec spec;
  std::vector<ConfigIssue> issues;
  std::set<std::string> failed_components;
};
ParsedPipeline parse_pipeline(const std::string& file, const std::vector<std::string>& overrides = {});
PipelineSpec load_pipeline_from_string(const std::string& yaml, const std::string& file_name,
                                       const std::vector<std::string>& overrides = {});

// "1ms", "20 ms", "12s", "500us", "2min", "100ns" -> nanoseconds; nullopt if not a duration.
std::optional<std::int64_t> parse_duration(const std::string& text);

}  // namespace wysiwyf
