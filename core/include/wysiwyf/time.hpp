#pragma once
/// @file
/// Time in the kernel: int64 nanoseconds, sim time from 0 or wall clock since the Unix epoch.
#include <cstdint>

namespace wysiwyf {

/// A point in time: int64 nanoseconds, sim time from 0 or wall clock since the Unix epoch.
struct Time {
  std::int64_t ns = 0;  ///< nanoseconds since the clock's origin
  /// The time in seconds.
  double seconds() const { return static_cast<double>(ns) * 1e-9; }
  /// The time `s` seconds after the origin (truncated to whole nanoseconds).
  static Time from_seconds(double s) { return Time{static_cast<std::int64_t>(s * 1e9)}; }
  /// The same time.
  friend bool operator==(Time a, Time b) { return a.ns == b.ns; }
  /// Not the same time.
  friend bool operator!=(Time a, Time b) { return a.ns != b.ns; }
  /// a is earlier than b.
  friend bool operator<(Time a, Time b) { return a.ns < b.ns; }
};

/// Nanoseconds in a second.
constexpr std::int64_t kNanosPerSecond = 1'000'000'000;

/// a - b in ns, saturated to the int64 range instead of wrapping: stamps from outside may be
/// anything, and a wrapped difference would read a sample from far in the future as long stale,
/// or an ancient one as fresh.
constexpr std::int64_t elapsed_ns(std::int64_t a, std::int64_t b) {
  // Within [-INT64_MAX, INT64_MAX]: symmetric, so std::abs of any result is defined.
  std::int64_t d = 0;
  if (__builtin_sub_overflow(a, b, &d)) return a < b ? -INT64_MAX : INT64_MAX;
  return d == INT64_MIN ? -INT64_MAX : d;
}

}  // namespace wysiwyf
