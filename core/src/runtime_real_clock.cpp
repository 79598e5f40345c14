// The real clock: one thread per component on absolute deadlines (or its doorbell), SCHED_FIFO and CPU pinning.
#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "runtime_impl.hpp"
#include "wysiwyf/real_time_throttling.hpp"
#include "wysiwyf/tick_deadline.hpp"

namespace wysiwyf {

namespace {

std::int64_t wall_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

void Runtime::Impl::set_fifo_priority(Slot& slot) {
  sched_param p{};
  p.sched_priority = slot.spec->priority.value;
  if (const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p); err != 0) {
    log(slot.spec->name, "priority " + std::to_string(p.sched_priority) +
                             " (SCHED_FIFO) refused: " + std::strerror(err) +
                             "; expected CAP_SYS_NICE or an rtprio limit (ulimit -r); running at normal priority");
    return;
  }
  // (a periodic thread's spin; a data-triggered one sleeps on its doorbell)
  const std::int64_t spin = !slot.doorbell && slot.spec->spin_ns.set ? slot.spec->spin_ns.value : 0;
  if (const std::string w = real_time_throttling_warning(spin, slot.period_ns, read_real_time_bandwidth()); !w.empty())
    log(slot.spec->name, "priority " + std::to_string(p.sched_priority) + ": " + w);
}

void Runtime::Impl::set_cpus(Slot& slot) {
  cpu_set_t set;
  CPU_ZERO(&set);
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  std::string list;
  for (int cpu : slot.spec->cpus.value) {
    list += (list.empty() ? "" : ", ") + std::to_string(cpu);
    if (cpu >= online) {
      log(slot.spec->name, "cpus: CPU " + std::to_string(cpu) + " does not exist (this machine has " +
                               std::to_string(online) + ", 0 to " + std::to_string(online - 1) +
                               "); the thread is not pinned");
      return;
    }
    CPU_SET(cpu, &set);
  }
  if (const int err = pthread_setaffinity_np(pthread_self(), sizeof(set), &set); err != 0)
    log(slot.spec->name, "cpus [" + list + "] refused: " + std::strerror(err) + "; the thread is not pinned");
}

void Runtime::Impl::run_real(RunResult& result) {
  const auto start = Clock::now();
  flush_after_tick = true;
  bridge->send_in_batches(true);  // to monitors: no wake of the publisher after every tick
  std::vector<std::thread> threads;
  for (auto& slot_ptr : slots) {
    Slot* slot = slot_ptr.get();
    threads.emplace_back([this, slot, start] {
      prctl(PR_SET_TIMERSLACK, 1UL);  // by default Linux may wake this thread up to 50 us late
      if (slot->spec->priority.set) set_fifo_priority(*slot);
      if (slot->spec->cpus.set) set_cpus(*slot);
      if (slot->doorbell) {  // data-triggered: one tick per ring; late = from the sample's arrival
        using Wake = detail::Doorbell::Wake;
        const auto timeout = std::chrono::nanoseconds(slot->trigger_timeout_ns);
        Clock::time_point rang;
        auto until = slot->trigger_timeout_ns ? Clock::now() + timeout : Clock::time_point::max();
        for (Wake w; (w = slot->doorbell->wait(rang, until)) != Wake::kStopped && !stopping.load();) {
          // A watchdog tick after a silence is on time; a ring's is late by the wait for the thread.
          const double late_us =
              w == Wake::kRang ? std::chrono::duration<double, std::micro>(Clock::now() - rang).count() : 0.0;
          tick(*slot, Time{wall_now_ns()}, late_us);
          if (slot->trigger_timeout_ns) until = Clock::now() + timeout;
        }
        return;
      }
      const auto period = std::chrono::nanoseconds(slot->period_ns);
      // The kernel wakes a sleeping thread tens of microseconds late (hundreds at times on a
      // virtual machine); with `spin` the thread wakes that much early and busy-waits the rest.
      const auto spin = std::chrono::nanoseconds(slot->spec->spin_ns.set ? slot->spec->spin_ns.value : 0);
      auto next = start;
      while (true) {
        {
          std::unique_lock<std::mutex> lock(stop_mutex);
          // Absolute deadlines on a fixed grid: no drift, whatever each tick costs.
          if (stop_cv.wait_until(lock, next - spin, [this] { return stopping.load(); })) return;
        }
        if (!spin_until(next, stopping)) return;
        const double late_us = std::chrono::duration<double, std::micro>(Clock::now() - next).count();
        tick(*slot, Time{wall_now_ns()}, late_us);
        if (const auto missed = advance_deadline(next, period)) slot->stats.add_overruns(missed);
      }
    });
  }
  const std::int64_t duration = spec.duration_ns();
  auto next_diag = start;
  while (!stopping.load()) {
    if (stop_signal_received()) request_stop("", "signal");
    if (duration > 0 && Clock::now() - start >= std::chrono::nanoseconds(duration))
      request_stop("", "duration reached");
    if (Clock::now() >= next_diag) {
      publish_diagnostics(Time{wall_now_ns()}, 1.0, false);
      bridge->flush_soon();
      next_diag += std::chrono::seconds(1);
    }
    std::unique_lock<std::mutex> lock(stop_mutex);
    stop_cv.wait_for(lock, std::chrono::milliseconds(20), [this] { return stopping.load(); });
  }
  for (auto& th : threads) th.join();
  result.sim_time_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count();
}

}  // namespace wysiwyf
