#pragma once
// What a data-triggered component waits on: its trigger inputs ring it when a sample lands
// (from a local writer or from DDS); the executor ticks it once per ring it has not yet served
// (rings that come while it ticks fold into one more tick). With a timeout, a silence that long
// wakes it too (a watchdog tick).
#include <chrono>
#include <condition_variable>
#include <mutex>

namespace wysiwyf::detail {

class Doorbell {
 public:
  using Clock = std::chrono::steady_clock;

  void ring() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!pending_) first_ring_ = Clock::now();
      pending_ = true;
    }
    cv_.notify_one();
  }

  // Sim clock: whether it rang since the last take; clears it.
  bool take() {
    std::lock_guard<std::mutex> lock(mutex_);
    const bool was = pending_;
    pending_ = false;
    return was;
  }

  enum class Wake { kRang, kTimedOut, kStopped };

  // Real clock: waits for a ring, for `until` (Clock::time_point::max(): no timeout) or for
  // stop(). kRang: `rang_at` is when the first unserved ring came, for how late the tick starts.
  Wake wait(Clock::time_point& rang_at, Clock::time_point until = Clock::time_point::max()) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto woken = [this] { return pending_ || stopped_; };
    if (until == Clock::time_point::max())
      cv_.wait(lock, woken);
    else if (!cv_.wait_until(lock, until, woken))
      return Wake::kTimedOut;
    if (stopped_) return Wake::kStopped;
    pending_ = false;
    rang_at = first_ring_;
    return Wake::kRang;
  }

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopped_ = true;
    }
    cv_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool pending_ = false, stopped_ = false;
  Clock::time_point first_ring_{};
};

}  // namespace wysiwyf::detail
