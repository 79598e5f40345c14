#pragma once
// The wrist calibration's input as a file: the arm's joints and the sensor's averaged reading at
// each static pose (YAML; `wysiwyf calibrate wrist` reads it, `wysiwyf calibrate wrist-poses`
// writes the poses to take with zero readings to fill in):
//   readings:
//     - {label: pose 1, joints: [q1, ..., qn], wrench: [fx, fy, fz, tx, ty, tz]}
// joints in rad (m for a prismatic joint), the wrench in N and N m in the sensor frame as the
// sensor reports it (bias included). The label is optional ("pose <i>" otherwise).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "wrist_calibration/tool_load_fit.hpp"
#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot {

struct WristSample {
  std::string label;
  Eigen::VectorXd joints;
  Eigen::Matrix<double, 6, 1> wrench = Eigen::Matrix<double, 6, 1>::Zero();
};

// Reads the file; every sample must have `joints` joint values. Throws std::runtime_error
// "file:line:col: what; expected ..." for an unreadable file, a wrong key, type or count, a
// non-finite number, more than 10000 samples.
std::vector<WristSample> load_wrist_readings(const std::string& path, int joints);
std::vector<WristSample> load_wrist_readings_from_string(const std::string& yaml, const std::string& name, int joints);

// The file's text for these samples (round trips through load_wrist_readings).
std::string wrist_readings_yaml(const std::vector<WristSample>& samples);

// The fit's inputs: gravity in the sensor frame (frame f of the arm) at each sample's joints.
// Throws std::invalid_argument naming the sample whose joints lie outside the arm's limits.
std::vector<WristReading> wrist_readings(const ArmModel& arm, FrameId f, const std::vector<WristSample>& samples,
                                         const Eigen::Vector3d& gravity_base = standard_gravity());

}  // namespace wysiwyf::robot
