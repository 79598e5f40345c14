#include "arm_yield.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::haptics {

ArmYield::ArmYield(double rate, double max_compliance, double min_force)
    : rate_(rate), max_compliance_(max_compliance), min_force_(min_force) {}

void ArmYield::object_at(std::int64_t t_ns, const Eigen::Vector3d& position) {
  if (!object_.empty() && t_ns <= object_.back().t_ns) object_.clear();  // (time went back: a new run)
  object_.push_back({t_ns, position});
  if (object_.size() > kKept) object_.pop_front();
}

void ArmYield::measured(std::int64_t t_ns, const Eigen::Vector3d& plate, const Eigen::Vector3d& force, double dt) {
  const double f = force.norm();
  if (rate_ <= 0 || !(f >= min_force_) || !(dt > 0) || object_.empty()) return;
  // The object where it was when the plate was measured (the newest at or before t).
  const auto after = std::upper_bound(object_.begin(), object_.end(), t_ns,
                                      [](std::int64_t t, const Sample& s) { return t < s.t_ns; });
  if (after == object_.begin()) return;  // older than all kept: nothing to compare with
  const Eigen::Vector3d& object = std::prev(after)->position;
  // Led by c F, the plate sits (c_true - c) F beyond the object; along the force that is the
  // residual compliance.
  const double residual = (plate - object).dot(force) / (f * f);
  if (!std::isfinite(residual)) return;  // (a non-finite plate or force teaches nothing)
  compliance_ = std::clamp(compliance_ + std::min(1.0, rate_ * dt) * residual, 0.0, max_compliance_);
}

}  // namespace wysiwyf::haptics
