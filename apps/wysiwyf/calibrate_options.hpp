#pragma once
// `wysiwyf calibrate`: what its steps share: the board's options, a joint list option, the arm.
#include <memory>
#include <string>

#include <Eigen/Core>

#include "arm_model/arm_model.hpp"
#include "calibration/charuco_target.hpp"
#include "cli.hpp"

namespace wysiwyf::cli {

// --squares-x N --squares-y N --square M --marker M (the A4 board by default).
vision::calibration::CharucoSpec board_options(Args& args);

// "--name a,b,c" as `count` finite numbers; UsageError naming the option otherwise.
Eigen::VectorXd joints_option(Args& args, const std::string& name, int count);

// The arm of --urdf (found in the config path) with its tip frame `tip`; UsageError naming the file.
std::unique_ptr<robot::ArmModel> arm_option(Args& args, const std::string& tip);

// Refuses options nobody read (UsageError).
void no_unknown_options(const Args& args);

// The camera steps: intrinsics, camera-base, camera-base-poses, board (cmd_calibrate_camera.cpp).
int calibrate_camera_step(const std::string& step, Args& args);

}  // namespace wysiwyf::cli
