#pragma once
// scripts/bench runs the benchmarks for their figures; ctest runs every benchmark binary once in
// smoke mode (WYSIWYF_BENCH_SMOKE=1, bench/run_smoke.py) so that one that aborts or reports an
// error fails CI. In smoke mode the fixed iteration counts, minimum times and durations below
// shrink to a few; nothing else changes.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>

namespace wysiwyf::bench {

inline bool smoke() {
  static const bool on = std::getenv("WYSIWYF_BENCH_SMOKE") != nullptr;
  return on;
}
inline benchmark::IterationCount iterations(benchmark::IterationCount n) {
  return smoke() ? std::min<benchmark::IterationCount>(n, 50) : n;
}
inline double min_time(double seconds) { return smoke() ? 0.01 : seconds; }
inline std::chrono::milliseconds duration(std::chrono::milliseconds d) {
  return smoke() ? std::min(d, std::chrono::milliseconds(200)) : d;
}

}  // namespace wysiwyf::bench
