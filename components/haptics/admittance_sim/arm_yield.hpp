#pragma once
// The arm gives way under the user's push. A position-controlled arm holds its plate with the
// stiffness of its servo: pushed with F, the plate sits c F further along the push than it was
// sent (c: the arm's compliance at the plate, 0.08 mm/N for the simulated PUMA's 10 Hz servo),
// inside the held object's face while the user pushes and deepest where the push rises, against a
// wall. ArmYield learns c from the plate's measured pose, the object's pose at the same instant
// and the user's force, and leads the setpoint by it: the setpoint is the object's pose less c F,
// so the plate, given way, is where the object is. c adapts only while the user pushes (more than
// min_force), at `rate` (1/s) on the residual c would leave, and stays within [0, max_compliance].
#include <cstddef>
#include <cstdint>
#include <deque>

#include <Eigen/Core>

namespace wysiwyf::haptics {

class ArmYield {
 public:
  // rate: 1/s (0: c stays 0, nothing is led); max_compliance: m/N; min_force: N.
  ArmYield(double rate, double max_compliance, double min_force);

  // The held object's device position at t (every tick; kept for about 50 ms).
  void object_at(std::int64_t t_ns, const Eigen::Vector3d& position);
  // The plate measured at t (its sample's stamp) while the user's force on the object (base
  // frame) was `force`, dt seconds after the last one: c adapts.
  void measured(std::int64_t t_ns, const Eigen::Vector3d& plate, const Eigen::Vector3d& force, double dt);
  // Where the setpoint goes relative to the object's pose under the force now.
  Eigen::Vector3d lead(const Eigen::Vector3d& force) const { return -compliance_ * force; }
  double compliance() const { return compliance_; }  // m/N
  // A new attachment: the object's past is forgotten, c is kept (the same arm).
  void restart() { object_.clear(); }

 private:
  struct Sample {
    std::int64_t t_ns;
    Eigen::Vector3d position;
  };
  static constexpr std::size_t kKept = 64;
  double rate_, max_compliance_, min_force_;
  double compliance_ = 0;
  std::deque<Sample> object_;
};

}  // namespace wysiwyf::haptics
