#pragma once
// `wysiwyf calibrate`: what its steps share: the board's options, a joint list option, the arm.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "arm_model/arm_model.hpp"
#include "calibration/camera_file.hpp"
#include "calibration/charuco_target.hpp"
#include "calibration/flange_views_file.hpp"
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

// The option's value; UsageError "NAME: expected EXPECTED" when it is missing or empty.
std::string required(Args& args, const std::string& name, const std::string& expected);

// An image file as 8-bit grey; UsageError naming it when it cannot be read.
cv::Mat read_grey(const std::string& path);

// The images (png, jpg, bmp, tif) in `dir`, sorted by name, at most 1000; UsageError naming
// `option` otherwise.
std::vector<std::string> image_files(const std::string& option, const std::string& dir);

// The camera steps: intrinsics, stereo, camera-base, camera-base-poses, board, lamps (cmd_calibrate_camera.cpp).
int calibrate_camera_step(const std::string& step, Args& args);

// stereo: the pair's extrinsics and rectification (cmd_calibrate_stereo.cpp).
int calibrate_stereo(Args& args);

// lamps: the plate's lamps on the flange, into a copy of the URDF (cmd_calibrate_lamps.cpp).
int calibrate_lamps(Args& args);

// A view's image, its joints within the arm's limits and its size the camera's; UsageError naming
// the file and the view otherwise.
cv::Mat read_view(const vision::calibration::FlangeViewEntry& e, const std::string& views_file,
                  const robot::ArmModel& arm, const vision::calibration::CameraIntrinsics& camera);

// --camera FILE (found in the config path); UsageError naming it when it cannot be read.
vision::calibration::CameraFile camera_option(Args& args);

}  // namespace wysiwyf::cli
