#include "allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

// (GCC cannot see that these replace the global operators, and warns about malloc/free.)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<std::uint64_t> g_allocations{0};
std::atomic<std::uint64_t> g_allocated_bytes{0};
}  // namespace

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  g_allocated_bytes.fetch_add(n, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace wysiwyf::bench {

std::uint64_t allocation_count() { return g_allocations.load(std::memory_order_relaxed); }
std::uint64_t allocated_bytes() { return g_allocated_bytes.load(std::memory_order_relaxed); }

}  // namespace wysiwyf::bench
