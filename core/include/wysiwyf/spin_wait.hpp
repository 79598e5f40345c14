#pragma once
// The last stretch of a real-time tick's wait, spent busy: a sleeping thread wakes tens of
// microseconds after its deadline (hundreds at times on a virtual machine), a spinning one
// within about a microsecond. The executor sleeps until `spin` before a deadline and spins the
// rest (pipeline key `spin`); the haptics benchmark's 1 kHz loop does the same.
#include <atomic>
#include <chrono>

namespace wysiwyf {

// Returns false if `stop` became true before the deadline.
inline bool spin_until(std::chrono::steady_clock::time_point deadline, const std::atomic<bool>& stop) {
  while (std::chrono::steady_clock::now() < deadline)
    if (stop.load(std::memory_order_relaxed)) return false;
  return true;
}

}  // namespace wysiwyf
