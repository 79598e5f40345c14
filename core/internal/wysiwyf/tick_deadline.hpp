#pragma once
// The real-time executor's deadlines, shared with the benchmarks that measure its loop.
// - spin_until: the last stretch of a tick's wait, spent busy: a sleeping thread wakes tens of
//   microseconds after its deadline (hundreds at times on a virtual machine), a spinning one
//   within about a microsecond. The executor sleeps until `spin` before a deadline and spins
//   the rest (pipeline key `spin`).
// - advance_deadline: after a tick, the next deadline on the fixed grid; deadlines already
//   missed by a whole period are skipped and counted (overruns), so a stall is one late tick,
//   not a run of them.
#include <atomic>
#include <chrono>
#include <cstdint>

namespace wysiwyf {

// Returns false if `stop` became true before the deadline.
inline bool spin_until(std::chrono::steady_clock::time_point deadline, const std::atomic<bool>& stop) {
  while (std::chrono::steady_clock::now() < deadline)
    if (stop.load(std::memory_order_relaxed)) return false;
  return true;
}

// Moves `next` one period on, and past every deadline already gone; returns how many were skipped.
inline std::uint64_t advance_deadline(std::chrono::steady_clock::time_point& next, std::chrono::nanoseconds period) {
  next += period;
  const auto now = std::chrono::steady_clock::now();
  if (now < next) return 0;
  const auto missed = (now - next) / period + 1;
  next += missed * period;
  return static_cast<std::uint64_t>(missed);
}

}  // namespace wysiwyf
