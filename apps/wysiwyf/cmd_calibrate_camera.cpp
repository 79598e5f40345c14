// wysiwyf calibrate board | intrinsics | camera-base-poses | camera-base: the camera's steps (the
// board to print, its intrinsics from images of the board, the poses for and the fit of its pose in
// the robot's base frame), each writing the calibration file the pipelines read.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include <opencv2/imgcodecs.hpp>

#include "calibrate_options.hpp"
#include "calibration/board_detection.hpp"
#include "calibration/camera_file.hpp"
#include "calibration/flange_views_file.hpp"
#include "calibration/intrinsics_fit.hpp"
#include "calibration/robot_world_fit.hpp"
#include "calibration/robot_world_poses.hpp"
#include "wysiwyf/config_files.hpp"

namespace wysiwyf::cli {

std::string required(Args& args, const std::string& name, const std::string& expected) {
  const auto v = args.value(name);
  if (!v || v->empty()) throw UsageError(name + ": expected " + expected);
  return *v;
}

cv::Mat read_grey(const std::string& path) {
  const cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw UsageError("cannot read the image '" + path + "'");
  return image;
}

std::vector<std::string> image_files(const std::string& option, const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (e.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif"))
      files.push_back(e.path().string());
  }
  if (ec) throw UsageError(option + ": cannot list '" + dir + "': " + ec.message());
  if (files.size() > 1000)
    throw UsageError(option + ": " + std::to_string(files.size()) + " images; expected 1000 at most");
  std::sort(files.begin(), files.end());
  return files;
}

namespace cal = vision::calibration;

cal::CameraFile camera_option(Args& args) {
  const std::string path = required(args, "--camera", "the camera's calibration file (wysiwyf calibrate intrinsics)");
  try {
    return cal::load_camera_file(find_config_file(path));
  } catch (const std::exception& e) {
    throw UsageError(std::string("--camera: ") + e.what());
  }
}

cv::Mat read_view(const cal::FlangeViewEntry& e, const std::string& views_file, const robot::ArmModel& arm,
                  const cal::CameraIntrinsics& camera) {
  if (!arm.limits().within(e.joints, 1e-6))
    throw UsageError(views_file + ": " + e.label + ": joints outside the limits");
  const cv::Mat image = read_grey(e.image);
  if (image.size() != camera.size)
    throw UsageError(e.image + ": " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                     " px; expected the calibrated camera's " + std::to_string(camera.size.width) + "x" +
                     std::to_string(camera.size.height));
  return image;
}

namespace {

// board --out FILE.png [--pixels-per-square N] [board options]
int board(Args& args) {
  const cal::CharucoSpec spec = board_options(args);
  const int pps = static_cast<int>(whole_option(args, "--pixels-per-square", 331, 20, 2000, "20 to 2000 px"));
  const std::string out = required(args, "--out", "the image file to write (png)");
  no_unknown_options(args);
  const cal::CharucoTarget target(spec);
  cv::Mat page;
  cv::copyMakeBorder(target.texture(pps), page, pps / 2, pps / 2, pps / 2, pps / 2, cv::BORDER_CONSTANT, 255);
  if (!cv::imwrite(out, page)) throw UsageError("cannot write '" + out + "'");
  std::cout << "wrote " << out << ": " << spec.squares_x << " x " << spec.squares_y << " squares of "
            << spec.square * 1e3 << " mm (" << pps << " px each: " << pps * 25.4 / (spec.square * 1e3)
            << " dpi at that size); print at 100 %, measure a square, and pass its size as --square\n";
  return 0;
}

// intrinsics --images DIR --out FILE [board options] [limits]
int intrinsics(Args& args) {
  const cal::CharucoSpec spec = board_options(args);
  const std::string dir = required(args, "--images", "a folder of images of the board (png, jpg)");
  const std::string out = required(args, "--out", "the calibration file to write (yaml)");
  cal::IntrinsicsLimits limits;
  limits.min_views = static_cast<int>(whole_option(args, "--min-views", limits.min_views, 3, 1000, "3 or more"));
  limits.max_view_error = number_option(args, "--max-view-error", limits.max_view_error, 0, 100, "px");
  limits.max_rms = number_option(args, "--max-rms", limits.max_rms, 0, 100, "px");
  limits.min_coverage = number_option(args, "--min-coverage", limits.min_coverage, 0, 1, "a share, 0 to 1");
  no_unknown_options(args);
  const std::vector<std::string> files = image_files("--images", dir);
  const cal::CharucoTarget target(spec);
  std::vector<cal::BoardDetection> views;
  for (const std::string& f : files)
    views.push_back(cal::detect_board(read_grey(f), target, std::filesystem::path(f).filename().string()));
  const cal::IntrinsicsFit fit = cal::fit_intrinsics(views, target, limits);
  std::cout << cal::describe(fit, limits);
  if (!fit.accepted) return 1;
  cal::CameraFile file;
  file.intrinsics = fit.camera;
  cal::save_camera_file(out, file,
                        "wysiwyf calibrate intrinsics: " + std::to_string(views.size()) + " images of " + dir +
                            ", RMS reprojection error " + std::to_string(fit.rms) + " px");
  std::cout << "wrote " << out << "\n";
  return 0;
}

// The arm's frame `name`; UsageError naming the file when its URDF has none.
robot::FrameId frame_of(const robot::ArmModel& arm, const std::string& name) {
  try {
    return arm.frame(name);
  } catch (const std::out_of_range&) {
    throw UsageError("--urdf: " + arm.urdf_path() + " has no link '" + name + "'; expected the arm's flange");
  }
}

Eigen::Isometry3d nominal_flange_T_board(const robot::ArmModel& arm, robot::FrameId flange,
                                         const cal::CharucoTarget& target) {
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(arm.dof());
  return arm.fk(q, flange).inverse() * arm.fk(q, arm.frame("dev")) * cal::dev_T_board(target);
}

// camera-base-poses --camera FILE --home Q --out FILE [--count N] [--seed S] [--urdf U] [board options]
int camera_base_poses(Args& args) {
  const cal::CharucoSpec spec = board_options(args);
  const cal::CameraFile camera = camera_option(args);
  if (!camera.base_T_eye)
    throw UsageError("--camera: expected a base_T_eye in it, the camera's pose as measured roughly (a few cm)");
  const int count = static_cast<int>(whole_option(args, "--count", 20, 8, 200, "8 to 200 poses"));
  const auto seed = static_cast<unsigned>(whole_option(args, "--seed", 1, 0, 1L << 31, "a whole number"));
  const std::string out = required(args, "--out", "the views file to write (yaml)");
  const auto arm = arm_option(args, "dev");
  const Eigen::VectorXd home = joints_option(args, "--home", arm->dof());
  no_unknown_options(args);
  if (!arm->limits().within(home)) throw UsageError("--home: outside the arm's joint limits");
  const cal::CharucoTarget target(spec);
  std::mt19937 rng(seed);
  const robot::FrameId flange = frame_of(*arm, "flange");
  const auto poses = cal::robot_world_poses(*arm, home, flange, nominal_flange_T_board(*arm, flange, target),
                                            *camera.base_T_eye, camera.intrinsics, target, count, rng);
  std::ofstream o(out);
  o << "# The robot-world calibration's poses (wysiwyf calibrate camera-base-poses): move the arm to each\n"
       "# in turn (they keep the board in view; check the path is clear), let it settle, save the camera's\n"
       "# image as the file named. Then: wysiwyf calibrate camera-base --views THIS_FILE\nviews:\n";
  char buf[64];
  for (std::size_t i = 0; i < poses.size(); ++i) {
    std::snprintf(buf, sizeof buf, "pose_%02zu.png", i + 1);
    o << "  - image: " << buf << "\n    joints: [";
    for (int j = 0; j < poses[i].size(); ++j) {
      std::snprintf(buf, sizeof buf, "%s%.6f", j ? ", " : "", poses[i][j]);
      o << buf;
    }
    o << "]\n";
  }
  if (!o) throw UsageError("cannot write '" + out + "'");
  std::cout << "wrote " << poses.size() << " poses to " << out << "\n";
  return poses.size() == static_cast<std::size_t>(count) ? 0 : 1;
}

// camera-base --camera FILE --views FILE --out FILE [--urdf U] [board options] [limits]
int camera_base(Args& args) {
  const cal::CharucoSpec spec = board_options(args);
  cal::CameraFile camera = camera_option(args);
  const std::string views_file = required(args, "--views", "the views file (wysiwyf calibrate camera-base-poses)");
  const std::string out = required(args, "--out", "the calibration file to write (yaml)");
  cal::RobotWorldLimits limits;
  limits.min_poses = static_cast<int>(whole_option(args, "--min-poses", limits.min_poses, 3, 1000, "3 or more"));
  limits.max_pose_error = number_option(args, "--max-pose-error", limits.max_pose_error, 0, 100, "px");
  const auto arm = arm_option(args, "dev");
  no_unknown_options(args);
  std::vector<cal::FlangeViewEntry> entries;
  try {
    entries = cal::load_flange_views(views_file, arm->dof());
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
  const cal::CharucoTarget target(spec);
  const robot::FrameId flange = frame_of(*arm, "flange");
  std::vector<cal::FlangeView> views;
  for (const cal::FlangeViewEntry& e : entries) {
    const cv::Mat image = read_view(e, views_file, *arm, camera.intrinsics);
    const cal::BoardDetection d = cal::detect_board(image, target, e.label);
    views.push_back({e.label, arm->fk(e.joints, flange), d.corners, d.ids});
  }
  const cal::RobotWorldFit fit = cal::fit_robot_world(views, target, camera.intrinsics, limits);
  std::cout << cal::describe(fit, limits);
  if (!fit.accepted) return 1;
  camera.base_T_eye = fit.base_T_eye;
  cal::save_camera_file(out, camera,
                        "wysiwyf calibrate camera-base: " + std::to_string(views.size()) + " poses of " + views_file +
                            ", RMS reprojection error " + std::to_string(fit.rms) +
                            " px; base_T_eye: the camera in the robot's base frame (camera_fixed's extrinsics)");
  std::cout << "wrote " << out << "\n";
  return 0;
}

}  // namespace

int calibrate_camera_step(const std::string& step, Args& args) {
  if (step == "board") return board(args);
  if (step == "intrinsics") return intrinsics(args);
  if (step == "camera-base-poses") return camera_base_poses(args);
  if (step == "camera-base") return camera_base(args);
  if (step == "stereo") return calibrate_stereo(args);
  if (step == "lamps") return calibrate_lamps(args);
  throw UsageError("unknown step '" + step +
                   "'; expected one of wrist-poses, wrist, board, intrinsics, stereo, camera-base-poses, camera-base, "
                   "lamps");
}

}  // namespace wysiwyf::cli
