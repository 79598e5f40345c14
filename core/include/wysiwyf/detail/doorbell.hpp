#pragma once
// What a data-triggered component waits on: its trigger inputs ring it when a sample lands
// (from a local writer or from DDS); the executor ticks it once per ring it has not yet served
// (rings that come while it ticks fold into one more tick).
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

  // Real clock: waits for a ring or for stop() (true: rang; `rang_at` is when the first
  // unserved ring came, for how late the tick starts).
  bool wait(Clock::time_point& rang_at) {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [this] { return pending_ || stopped_; });
    if (stopped_) return false;
    pending_ = false;
    rang_at = first_ring_;
    return true;
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
