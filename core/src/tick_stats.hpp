#pragma once
// Tick durations, start lateness and counts of one component, summarised for Diagnostics.
// Thread-safe: the component's thread records, the diagnostics publisher reads.
#include <algorithm>
#include <array>
#include <cstdint>
#include <mutex>
#include <vector>

namespace wysiwyf::detail {

class TickStats {
 public:
  struct Summary {
    std::uint64_t ticks = 0;
    std::uint64_t overruns = 0;
    double p50_us = 0, p99_us = 0, max_us = 0;                 // tick durations
    double late_p50_us = 0, late_p99_us = 0, late_max_us = 0;  // start after the deadline (real clock)
    std::uint64_t window_ticks = 0;                            // ticks since the previous summary
  };

  void record(double duration_us, double late_us = 0) {
    std::lock_guard<std::mutex> lock(mutex_);
    late_[next_ % late_.size()] = static_cast<float>(late_us);
    samples_[next_++ % samples_.size()] = static_cast<float>(duration_us);
    ++ticks_;
    ++window_ticks_;
  }
  void add_overruns(std::uint64_t n) {
    std::lock_guard<std::mutex> lock(mutex_);
    overruns_ += n;
  }

  // Percentiles over the last 1024 ticks; resets the window count.
  Summary summarise() {
    std::lock_guard<std::mutex> lock(mutex_);
    Summary s;
    s.ticks = ticks_;
    s.overruns = overruns_;
    s.window_ticks = window_ticks_;
    window_ticks_ = 0;
    const std::size_t n = std::min<std::uint64_t>(ticks_, samples_.size());
    if (n == 0) return s;
    auto at = [&](double q) {
      auto k = static_cast<std::size_t>(q * static_cast<double>(n - 1) + 0.5);
      std::nth_element(scratch_.begin(), scratch_.begin() + k, scratch_.end());
      return static_cast<double>(scratch_[k]);
    };
    scratch_.assign(samples_.begin(), samples_.begin() + n);
    s.p50_us = at(0.50);
    s.p99_us = at(0.99);
    s.max_us = *std::max_element(scratch_.begin(), scratch_.end());
    scratch_.assign(late_.begin(), late_.begin() + n);
    s.late_p50_us = at(0.50);
    s.late_p99_us = at(0.99);
    s.late_max_us = *std::max_element(scratch_.begin(), scratch_.end());
    return s;
  }

 private:
  std::mutex mutex_;
  std::array<float, 1024> samples_{}, late_{};
  std::vector<float> scratch_;
  std::uint64_t next_ = 0, ticks_ = 0, overruns_ = 0, window_ticks_ = 0;
};

}  // namespace wysiwyf::detail
