#include "keyframes/keyframes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wysiwyf::io {

Keyframes::Keyframes(const std::vector<double>& flat, int values_per_row) : width_(values_per_row) {
  const std::size_t row = static_cast<std::size_t>(values_per_row) + 1;
  if (flat.empty() || flat.size() % row != 0)
    throw std::invalid_argument("found " + std::to_string(flat.size()) + " values; expected whole rows of " +
                                std::to_string(row) + " values (at least 1): a time in s, then " +
                                std::to_string(values_per_row) + " values");
  for (std::size_t i = 0; i < flat.size(); i += row) {
    const double t = flat[i];
    if (times_.empty() && t != 0.0)
      throw std::invalid_argument("the first row's time is " + std::to_string(t) + "; expected 0");
    if (!times_.empty() && !(t > times_.back()))
      throw std::invalid_argument("row " + std::to_string(times_.size()) + " has time " + std::to_string(t) +
                                  ", not after the previous row's " + std::to_string(times_.back()) +
                                  "; expected strictly increasing times");
    times_.push_back(t);
    values_.insert(values_.end(), flat.begin() + static_cast<long>(i) + 1, flat.begin() + static_cast<long>(i + row));
  }
}

Keyframes::Segment Keyframes::at(double t) const {
  const int last = rows() - 1;
  if (t >= times_.back()) return Segment{last, last, 1.0, 0.0};
  if (t <= 0) return Segment{0, std::min(1, last), 0.0, last > 0 ? times_[1] - times_[0] : 0.0};
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  const int to = static_cast<int>(it - times_.begin());
  const int from = to - 1;
  const double duration = times_[to] - times_[from];
  return Segment{from, to, (t - times_[from]) / duration, duration};
}

}  // namespace wysiwyf::io
