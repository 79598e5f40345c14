#pragma once
// The kernel's bandwidth limit on real-time threads, and the executor's one pitfall with it.
// Linux lets SCHED_FIFO/SCHED_RR threads run at most sched_rt_runtime_us of every
// sched_rt_period_us (/proc/sys/kernel; 950000 of 1000000 by default) and stops them for the rest
// of the period. A component with `priority` whose `spin` covers its whole period never sleeps,
// so it is stopped for the rest of every period: tens of its ticks missed at once (measured in
// docs/design/haptic-loop-thread.md).
#include <cstdint>
#include <string>

namespace wysiwyf {

struct RealTimeBandwidth {
  std::int64_t runtime_us = -1;  // -1: no limit (or none known)
  std::int64_t period_us = 0;
};

// /proc/sys/kernel/sched_rt_runtime_us and sched_rt_period_us; no limit where they cannot be read.
RealTimeBandwidth read_real_time_bandwidth();

// What to say about a SCHED_FIFO thread that spins `spin_ns` before each deadline of a `period_ns`
// period under `limit`; empty where the thread sleeps in each period or the kernel sets no limit.
std::string real_time_throttling_warning(std::int64_t spin_ns, std::int64_t period_ns, const RealTimeBandwidth& limit);

}  // namespace wysiwyf
