#pragma once
// Samples of one figure over a run: nearest-rank percentiles, and the largest with its time.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace wysiwyf::display::stats {

class Percentiles {
 public:
  void add(double value, std::int64_t t_ns = 0) {
    if (values_.empty() || value > max_) max_ = value, max_at_ = t_ns;
    values_.push_back(value);
  }
  std::size_t samples() const { return values_.size(); }
  // p in [0, 100]; 0 without samples.
  double percentile(double p) const {
    if (values_.empty()) return 0;
    const auto rank = static_cast<std::size_t>(std::ceil(std::clamp(p, 0.0, 100.0) / 100 * values_.size()));
    const auto k = values_.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(rank, 1) - 1);
    std::nth_element(values_.begin(), k, values_.end());
    return *k;
  }
  double max() const { return max_; }
  std::int64_t max_at() const { return max_at_; }

 private:
  mutable std::vector<double> values_;  // reordered by percentile()
  double max_ = 0;
  std::int64_t max_at_ = 0;
};

}  // namespace wysiwyf::display::stats
