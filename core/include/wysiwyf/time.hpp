#pragma once
// Time in the kernel: int64 nanoseconds, sim time from 0 or wall clock since the Unix epoch.
#include <cstdint>

namespace wysiwyf {

struct Time {
  std::int64_t ns = 0;
  double seconds() const { return static_cast<double>(ns) * 1e-9; }
  static Time from_seconds(double s) { return Time{static_cast<std::int64_t>(s * 1e9)}; }
  friend bool operator==(Time a, Time b) { return a.ns == b.ns; }
  friend bool operator!=(Time a, Time b) { return a.ns != b.ns; }
  friend bool operator<(Time a, Time b) { return a.ns < b.ns; }
};

constexpr std::int64_t kNanosPerSecond = 1'000'000'000;

}  // namespace wysiwyf
