#include "registration_stats.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::display {

RegistrationError registration_error(const Eigen::Isometry3d& want, const Eigen::Isometry3d& plate) {
  return {(want.translation() - plate.translation()).norm() * 1e3,
          Eigen::Quaterniond(want.linear()).angularDistance(Eigen::Quaterniond(plate.linear())) * 180 / M_PI};
}

void RegistrationStats::add(RegistrationError e, std::int64_t t_ns) {
  mm_.push_back(e.mm);
  if (e.mm > max_mm_) max_mm_ = e.mm, max_at_ = t_ns;
  max_deg_ = std::max(max_deg_, e.deg);
}

double RegistrationStats::percentile_mm(double p) const {
  if (mm_.empty()) return 0;
  const auto rank = static_cast<std::size_t>(std::ceil(std::clamp(p, 0.0, 100.0) / 100 * mm_.size()));
  const auto k = mm_.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(rank, 1) - 1);
  std::nth_element(mm_.begin(), k, mm_.end());
  return *k;
}

}  // namespace wysiwyf::display
