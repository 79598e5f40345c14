#pragma once
// Counts every operator new in a benchmark process (linking allocation_counter.cpp replaces the
// global operators), so a benchmark can report heap allocations per call or per hop.
#include <cstdint>

namespace wysiwyf::bench {

std::uint64_t allocation_count();
std::uint64_t allocated_bytes();

}  // namespace wysiwyf::bench
