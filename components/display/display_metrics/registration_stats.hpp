#pragma once
// Haptic registration while the device is attached to a virtual object: the real plate against
// where the attachment holds it on the moving object (base_T_obj * obj_T_dev), sample by sample,
// summed up as percentiles.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace wysiwyf::display {

struct RegistrationError {
  double mm = 0;   // plate origin from where it should be
  double deg = 0;  // plate orientation from it
};

RegistrationError registration_error(const Eigen::Isometry3d& want, const Eigen::Isometry3d& plate);

class RegistrationStats {
 public:
  void add(RegistrationError e, std::int64_t t_ns = 0);
  std::size_t samples() const { return mm_.size(); }
  // Nearest-rank percentile of the position errors, p in [0, 100]; 0 without samples.
  double percentile_mm(double p) const;
  double max_mm() const { return max_mm_; }
  double max_deg() const { return max_deg_; }
  std::int64_t max_mm_at() const { return max_at_; }  // when the largest position error was

 private:
  mutable std::vector<double> mm_;  // reordered by percentile_mm
  double max_mm_ = 0, max_deg_ = 0;
  std::int64_t max_at_ = 0;
};

}  // namespace wysiwyf::display
