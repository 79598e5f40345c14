#pragma once
// What a tick cost the thread that ran it, beside its wall time, for telling a component's own
// work from what other threads and processes did to it: the thread's CPU time and, where the
// kernel lets this process count them (perf events: not in most virtual machines), the
// user-space instructions it retired. Neither depends on what else the machine is running
// the way a wall-clock time does.
#include <cstdint>

namespace wysiwyf::detail {

struct TickCost {
  double cpu_us = 0;         // the thread's CPU time
  double instructions = -1;  // user-space instructions retired; < 0: not counted here
};

// The calling thread's counters now (its instruction counter is opened on the first call on each
// thread); the difference of two readings on one thread is what ran between them.
TickCost thread_cost_now();
inline TickCost operator-(const TickCost& a, const TickCost& b) {
  return {a.cpu_us - b.cpu_us, a.instructions < 0 || b.instructions < 0 ? -1 : a.instructions - b.instructions};
}

}  // namespace wysiwyf::detail
