#pragma once
// Runs a benchmark's call over a fixed set of prepared inputs, cycled (so nothing is learnt from
// one input), and reports the operator new calls per call (allocs_per_call; the hot calls of the
// models must make none). Linked with allocation_counter.cpp.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>

#include "allocation_counter.hpp"

namespace wysiwyf::bench {

// Calls call(i) once per iteration, i cycling through [0, inputs).
template <typename Call>
void run_per_call(benchmark::State& state, std::size_t inputs, Call call) {
  std::size_t i = 0;
  const std::uint64_t allocs_before = allocation_count();
  for (auto _ : state) {
    call(i);
    i = (i + 1) % inputs;
  }
  state.counters["allocs_per_call"] = benchmark::Counter(static_cast<double>(allocation_count() - allocs_before) /
                                                         static_cast<double>(state.iterations()));
}

}  // namespace wysiwyf::bench
