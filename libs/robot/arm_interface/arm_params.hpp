#pragma once
// The parameters arm_sim and puma_driver declare alike (the robot file and the tip frame, the
// Cartesian tracker's bandwidth, the safety gate's limits), and the arm model they load from
// them: any serial arm's URDF (ArmModel). One declaration, so both components describe and check
// them the same way.
#include <memory>
#include <string>
#include <vector>

#include "arm_model/arm_model.hpp"
#include "safety_gate/safety_gate.hpp"
#include "wysiwyf/context.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot {

struct ArmParams {
  std::string urdf_path;                    // robot URDF (found on the config path)
  std::string tip_frame;                    // the frame the Cartesian setpoints place, fixed to the last body
  double tracker_hz = 10;                   // natural frequency of the critically damped setpoint tracker
  std::vector<double> acceleration_limits;  // one per joint, rad/s^2 (checked against the URDF's joints)
  SafetyConfig gate;            // limits from the URDF and acceleration_limits are filled in by load_arm_model
  std::string setpoint_source;  // setpoints whose source does not begin so are refused ("": any)

  // Why a setpoint is refused for its source, or empty.
  std::string source_problem(const msg::CartesianSetpoint& m) const;
};

ArmParams declare_arm_params(Context& ctx);

// Loads the arm of `params` with its tip frame (which must be fixed to the last body), gives the
// gate the URDF's joint limits, acceleration_limits (one per joint) and the component's period,
// and checks the gate's configuration. What is wrong is rejected at its parameter
// (Context::reject); then it returns null.
std::unique_ptr<ArmModel> load_arm_model(Context& ctx, ArmParams& params);

}  // namespace wysiwyf::robot
