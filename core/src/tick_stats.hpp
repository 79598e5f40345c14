#pragma once
// Tick durations, start lateness and counts of one component, summarised for Diagnostics (the
// last 1024 ticks) and for the run's report (tick durations over the whole run as well, in bins
// 1 % wide; and, where measured, each tick's cost to its thread: tick_cost.hpp). Thread-safe:
// the component's thread records, the diagnostics publisher reads.
#include <algorithm>
#include <array>
#include <cmath>
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
    // Over the whole run: the tick duration's 99th percentile (at most 1 % above the true
    // value: the upper edge of its bin, or the longest tick if less) and the longest tick.
    double run_p99_us = 0, run_max_us = 0;
    // The last 1024 ticks' cost to their thread (RunOptions::measure_tick_cost; < 0: not measured).
    double cpu_p50_us = -1, cpu_p99_us = -1;
    double instructions_p50 = -1, instructions_p99 = -1;
  };

  // `cpu_us`, `instructions`: what the tick cost its thread, < 0 where not measured.
  void record(double duration_us, double late_us = 0, double cpu_us = -1, double instructions = -1) {
    std::lock_guard<std::mutex> lock(mutex_);
    late_[next_ % late_.size()] = static_cast<float>(late_us);
    cpu_[next_ % cpu_.size()] = static_cast<float>(cpu_us);
    instructions_[next_ % instructions_.size()] = static_cast<float>(instructions);
    samples_[next_++ % samples_.size()] = static_cast<float>(duration_us);
    ++run_bins_[bin_of(duration_us)];
    run_max_us_ = std::max(run_max_us_, duration_us);
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
    // A cost is reported only where every tick of the window had it measured.
    scratch_.assign(cpu_.begin(), cpu_.begin() + n);
    if (*std::min_element(scratch_.begin(), scratch_.end()) >= 0) s.cpu_p50_us = at(0.50), s.cpu_p99_us = at(0.99);
    scratch_.assign(instructions_.begin(), instructions_.begin() + n);
    if (*std::min_element(scratch_.begin(), scratch_.end()) >= 0)
      s.instructions_p50 = at(0.50), s.instructions_p99 = at(0.99);
    s.run_max_us = run_max_us_;
    s.run_p99_us = std::min(run_max_us_, run_percentile(0.99));
    return s;
  }

 private:
  // Bin 0: up to 1 us; bin b: (1.01^(b-1), 1.01^b] us; the last also holds everything longer (10 s on).
  static constexpr std::size_t kRunBins = 1622;
  static std::size_t bin_of(double us) {
    if (!(us > 1.0)) return 0;
    const double b = std::ceil(std::log(us) / std::log(1.01));
    return b >= static_cast<double>(kRunBins - 1) ? kRunBins - 1 : static_cast<std::size_t>(b);
  }
  // The upper edge of the bin holding the q-quantile of every tick so far.
  double run_percentile(double q) const {
    const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(ticks_)));
    std::uint64_t seen = 0;
    for (std::size_t b = 0; b < kRunBins; ++b)
      if ((seen += run_bins_[b]) >= std::max<std::uint64_t>(rank, 1)) return std::pow(1.01, static_cast<double>(b));
    return run_max_us_;
  }

  std::mutex mutex_;
  std::array<std::uint64_t, kRunBins> run_bins_{};
  double run_max_us_ = 0;
  std::array<float, 1024> samples_{}, late_{}, cpu_{}, instructions_{};
  std::vector<float> scratch_;
  std::uint64_t next_ = 0, ticks_ = 0, overruns_ = 0, window_ticks_ = 0;
};

}  // namespace wysiwyf::detail
