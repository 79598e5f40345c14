#pragma once
// The arm as a hand meets it: the PUMA's links as capsules along the segments between its joint
// origins (as camera_sim draws them), the wrist with the sensor, the plate as a thin box and its
// knob; for a point (the hand), how far each part's surface is and how fast its nearest point
// approaches. What speed and separation monitoring (ISO/TS 15066) needs, for the surface
// planner, the tests and the display's metrics alike.
#include <array>
#include <string>

#include <Eigen/Geometry>

#include "puma_model/puma_model.hpp"

namespace wysiwyf::robot {

struct PartClearance {
  const char* name = "";
  double distance = 0;                                // m from the part's surface to the point (0 inside)
  Eigen::Vector3d nearest = Eigen::Vector3d::Zero();  // the part's point nearest the point (its axis or face), base
  double approach_speed = 0;                          // m/s of that point toward the point (negative: moving away)
};

class ArmClearance {
 public:
  static constexpr int kParts = 6;  // upper arm, forearm, wrist, sensor, plate, knob

  // plate_half: the plate's half size in dev x and y; knob_length/radius: along dev z.
  explicit ArmClearance(const PumaModel& model, Eigen::Vector2d plate_half = {0.1, 0.1}, double knob_length = 0.04,
                        double knob_radius = 0.015);

  // Every part's clearance to `point` with the arm at q moving at qd.
  std::array<PartClearance, kParts> evaluate(const Vector6d& q, const Vector6d& qd, const Eigen::Vector3d& point) const;
  // The part nearest `point`.
  static const PartClearance& nearest(const std::array<PartClearance, kParts>& parts);

 private:
  const PumaModel& model_;
  FrameId link1_, link3_, link4_, flange_, dev_;
  Eigen::Vector2d plate_half_;
  double knob_length_, knob_radius_;
};

}  // namespace wysiwyf::robot
