#include "tick_cost.hpp"

#include <linux/perf_event.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <cstring>

namespace wysiwyf::detail {

namespace {

// The calling thread's counter of user-space instructions, or -1 where there is none.
int open_instruction_counter() {
  perf_event_attr attr;
  std::memset(&attr, 0, sizeof(attr));
  attr.type = PERF_TYPE_HARDWARE;
  attr.size = sizeof(attr);
  attr.config = PERF_COUNT_HW_INSTRUCTIONS;
  attr.exclude_kernel = 1;
  attr.exclude_hv = 1;
  return static_cast<int>(syscall(SYS_perf_event_open, &attr, 0 /* this thread */, -1 /* any CPU */, -1, 0));
}

// Closes the thread's counter when the thread ends.
struct ThreadCounter {
  int fd = open_instruction_counter();
  ~ThreadCounter() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

TickCost thread_cost_now() {
  thread_local ThreadCounter counter;
  TickCost c;
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  c.cpu_us = static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
  std::uint64_t n = 0;
  if (counter.fd >= 0 && ::read(counter.fd, &n, sizeof(n)) == static_cast<ssize_t>(sizeof(n)))
    c.instructions = static_cast<double>(n);
  return c;
}

}  // namespace wysiwyf::detail
