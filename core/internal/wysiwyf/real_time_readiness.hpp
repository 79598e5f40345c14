#pragma once
// What a real-clock pipeline asks of the machine (its fast loops, spinning and SCHED_FIFO
// threads) against what the machine gives (CPUs, the permission to raise a priority, timer
// slack, the kernel's real-time bandwidth): said by `wysiwyf run` at start.
#include <string>
#include <vector>

#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/real_time_throttling.hpp"

namespace wysiwyf {

struct MachineFacts {
  int cpus_online = 1;
  int cpus_allowed = 1;         // this process's affinity
  bool cap_sys_nice = false;    // may set any SCHED_FIFO priority
  int rtprio_limit = 0;         // RLIMIT_RTPRIO (ulimit -r): the highest priority allowed without it
  long timer_slack_ns = 50000;  // the process's default (each component thread sets 1 ns)
  RealTimeBandwidth bandwidth;
};

MachineFacts read_machine_facts();

// A loop at this rate or more, or one that spins, wants a CPU of its own.
constexpr double kFastLoopHz = 500;

// One line each: the fast loops and the CPUs, SCHED_FIFO, timer slack. `process`: the group this
// process runs ("" all). `warning` set where the machine cannot give what the pipeline asks.
struct ReadinessLine {
  std::string text;
  bool warning = false;
};
std::vector<ReadinessLine> real_time_readiness(const PipelineSpec& spec, const std::string& process,
                                               const MachineFacts& machine);

}  // namespace wysiwyf
