#pragma once
// The wrist wrench from the UR e-Series' built-in force/torque sensor, as the display's other
// wrist sensors give it: the controller's actual_TCP_force is the wrench at the TCP with base
// axes (N, N m), the payload set on the pendant compensated. The driver takes the pendant's TCP to
// be the tool flange (no TCP offset: set it so), turns the wrench into the URDF's sensor frame
// (ft_sensor) about that frame's origin, and adds back the weight of the tool the display's
// consumers expect in a wrist reading (the supervisor and admittance_sim take the scene's
// tool_mass out themselves, as for an ATI Net F/T); the rest of the pendant's payload stays
// compensated. Bias: the controller's own zero (zero_ftsensor(), or the pendant) with the arm at
// rest; nothing is subtracted here.
#include <array>
#include <string>

#include <Eigen/Geometry>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot::ur {

struct Payload {
  double mass = 0;                                       // kg: the tool the reading carries
  Eigen::Vector3d com_flange = Eigen::Vector3d::Zero();  // m, its centre of gravity in the flange frame
};

class TcpWrench {
 public:
  // Throws std::out_of_range when the model lacks `flange_frame` or `sensor_frame`.
  TcpWrench(const ArmModel& model, const std::string& flange_frame, const std::string& sensor_frame,
            const Payload& payload);

  // The reading in the sensor frame about its origin, for the measured joints q.
  void to_sensor(const JointVector& q, const std::array<double, 6>& tcp_force, Eigen::Vector3d& force,
                 Eigen::Vector3d& torque) const;

 private:
  const ArmModel& model_;
  FrameId flange_, sensor_;
  Payload payload_;
};

}  // namespace wysiwyf::robot::ur
