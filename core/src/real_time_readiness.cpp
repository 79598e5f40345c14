// What a real-clock pipeline asks of the machine, and what the machine gives (real_time_readiness).
#include "wysiwyf/real_time_readiness.hpp"

#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace wysiwyf {

namespace {

constexpr int kCapSysNice = 23;  // linux/capability.h

bool has_cap_sys_nice() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("CapEff:", 0) == 0) {
      unsigned long long caps = 0;
      std::istringstream(line.substr(7)) >> std::hex >> caps;
      return (caps >> kCapSysNice) & 1ULL;
    }
  return false;
}

std::string names(const std::vector<std::string>& list) {
  std::string out;
  for (std::size_t i = 0; i < list.size() && i < 6; ++i) out += (i ? ", " : "") + list[i];
  if (list.size() > 6) out += " and " + std::to_string(list.size() - 6) + " more";
  return out;
}

}  // namespace

MachineFacts read_machine_facts() {
  MachineFacts m;
  m.cpus_online = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  cpu_set_t set;
  m.cpus_allowed = sched_getaffinity(0, sizeof(set), &set) == 0 ? CPU_COUNT(&set) : m.cpus_online;
  m.cap_sys_nice = has_cap_sys_nice();
  rlimit limit{};
  if (getrlimit(RLIMIT_RTPRIO, &limit) == 0)
    m.rtprio_limit = limit.rlim_cur == RLIM_INFINITY ? 99 : static_cast<int>(std::min<rlim_t>(limit.rlim_cur, 99));
  const int slack = prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0);
  if (slack >= 0) m.timer_slack_ns = slack;
  m.bandwidth = read_real_time_bandwidth();
  return m;
}

std::vector<ReadinessLine> real_time_readiness(const PipelineSpec& spec, const std::string& process,
                                               const MachineFacts& machine) {
  std::vector<std::string> fast, fifo;
  int highest = 0;
  for (const auto& c : spec.components) {
    if (!c.is_enabled() || (!process.empty() && c.process_name() != process)) continue;
    const bool spins = c.spin_ns.set && c.spin_ns.value > 0 && !c.is_triggered();
    if (spins || (c.rate.set && c.rate.value >= kFastLoopHz && !c.is_triggered())) fast.push_back(c.name);
    if (c.priority.set) {
      fifo.push_back(c.name);
      highest = std::max(highest, c.priority.value);
    }
  }
  std::vector<ReadinessLine> lines;
  const std::string cpus = std::to_string(machine.cpus_allowed) + " CPU(s) for this process (" +
                           std::to_string(machine.cpus_online) + " online)";
  if (fast.empty())
    lines.push_back({"real time: " + cpus + "; no loop at " + std::to_string(static_cast<int>(kFastLoopHz)) +
                     " Hz or more, none spinning"});
  else if (static_cast<int>(fast.size()) < machine.cpus_allowed)
    lines.push_back({"real time: " + cpus + " for " + std::to_string(fast.size()) + " fast loop(s) (" + names(fast) +
                     "): each can have a CPU of its own, " +
                     std::to_string(machine.cpus_allowed - static_cast<int>(fast.size())) + " left for the rest"});
  else
    lines.push_back({"real time: " + cpus + " for " + std::to_string(fast.size()) + " fast loop(s) (" + names(fast) +
                         "): they share CPUs with each other and the rest, so expect late ticks under load; a "
                         "display wants a CPU per fast loop and more for the rest (docs/deployment.md, The machine)",
                     true});
  if (fifo.empty()) {
    lines.push_back(
        {std::string("real time: no component asks for SCHED_FIFO (priority:); ") +
         (machine.cap_sys_nice || machine.rtprio_limit > 0 ? "this process may raise priorities"
                                                           : "this process could not (no CAP_SYS_NICE, ulimit -r 0)")});
  } else if (machine.cap_sys_nice || machine.rtprio_limit >= highest) {
    lines.push_back(
        {"real time: SCHED_FIFO for " + names(fifo) + " (up to priority " + std::to_string(highest) + "): allowed (" +
         (machine.cap_sys_nice ? std::string("CAP_SYS_NICE") : "ulimit -r " + std::to_string(machine.rtprio_limit)) +
         ")"});
  } else {
    lines.push_back({"real time: SCHED_FIFO for " + names(fifo) + " (up to priority " + std::to_string(highest) +
                         "): refused here (no CAP_SYS_NICE, ulimit -r " + std::to_string(machine.rtprio_limit) +
                         "): they run at normal priority; expected root, setcap cap_sys_nice+ep on the program, "
                         "or an rtprio limit in /etc/security/limits.conf",
                     true});
  }
  std::string slack = "real time: timer slack " + std::to_string(machine.timer_slack_ns / 1000) +
                      " us for this process, 1 ns for each component's thread (it wakes on time, not up to " +
                      std::to_string(machine.timer_slack_ns / 1000) + " us late)";
  if (machine.bandwidth.runtime_us >= 0 && machine.bandwidth.period_us > 0 && !fifo.empty())
    slack += "; the kernel lets real-time threads run " + std::to_string(machine.bandwidth.runtime_us) + " of every " +
             std::to_string(machine.bandwidth.period_us) + " us";
  lines.push_back({slack});
  return lines;
}

}  // namespace wysiwyf
