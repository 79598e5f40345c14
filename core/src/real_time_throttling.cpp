#include "wysiwyf/real_time_throttling.hpp"

#include <fstream>

namespace wysiwyf {
namespace {

std::int64_t read_number(const char* path, std::int64_t otherwise) {
  std::ifstream in(path);
  std::int64_t v = 0;
  return in >> v ? v : otherwise;
}

}  // namespace

RealTimeBandwidth read_real_time_bandwidth() {
  RealTimeBandwidth b;
  b.period_us = read_number("/proc/sys/kernel/sched_rt_period_us", 0);
  b.runtime_us = b.period_us > 0 ? read_number("/proc/sys/kernel/sched_rt_runtime_us", -1) : -1;
  return b;
}

std::string real_time_throttling_warning(std::int64_t spin_ns, std::int64_t period_ns, const RealTimeBandwidth& limit) {
  if (period_ns <= 0 || spin_ns < period_ns) return "";  // it sleeps in each period
  if (limit.runtime_us < 0 || limit.period_us <= 0 || limit.runtime_us >= limit.period_us) return "";
  const std::int64_t stall_ms = (limit.period_us - limit.runtime_us) / 1000;
  return "spin covers the whole period, so this SCHED_FIFO thread never sleeps, and the kernel lets real-time "
         "threads run only " +
         std::to_string(limit.runtime_us) + " of every " + std::to_string(limit.period_us) +
         " us (/proc/sys/kernel/sched_rt_runtime_us): it will be stopped for about " + std::to_string(stall_ms) +
         " ms every " + std::to_string(limit.period_us / 1000) +
         " ms, missing those periods; expected a spin below the period (such as 100us), no priority, or "
         "sched_rt_runtime_us set to -1";
}

}  // namespace wysiwyf
