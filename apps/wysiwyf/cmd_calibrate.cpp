// wysiwyf calibrate STEP: each step reads recorded data, prints its residual report and writes the
// file the pipelines read only when the result passes its limits (exit 0); a refused result exits
// 1 with the reason, a usage or input-file mistake 2. Here the wrist sensor's steps and the
// options the steps share; the camera steps are in cmd_calibrate_camera.cpp.
#include <fstream>
#include <iostream>
#include <sstream>

#include "calibrate_options.hpp"
#include "wrist_calibration/scene_tool_load.hpp"
#include "wrist_calibration/tool_load_fit.hpp"
#include "wrist_calibration/wrist_poses.hpp"
#include "wrist_calibration/wrist_readings_file.hpp"
#include "wysiwyf/config_files.hpp"

namespace wysiwyf::cli {

vision::calibration::CharucoSpec board_options(Args& args) {
  vision::calibration::CharucoSpec s;
  s.squares_x = static_cast<int>(whole_option(args, "--squares-x", s.squares_x, 3, 30, "3 to 30 squares"));
  s.squares_y = static_cast<int>(whole_option(args, "--squares-y", s.squares_y, 3, 30, "3 to 30 squares"));
  s.square = number_option(args, "--square", s.square, 0.005, 1, "a square's side in m, 0.005 to 1");
  s.marker = number_option(args, "--marker", s.square * 0.75, 0.0015, 0.9, "a marker's side in m");
  if (const std::string p = vision::calibration::problem(s); !p.empty()) throw UsageError(p);
  return s;
}

Eigen::VectorXd joints_option(Args& args, const std::string& name, int count) {
  const auto v = args.value(name);
  if (!v) throw UsageError(name + ": expected " + std::to_string(count) + " joint values, comma-separated (rad, m)");
  std::vector<double> q;
  std::stringstream in(*v);
  for (std::string item; std::getline(in, item, ',');) {
    try {
      std::size_t used = 0;
      const double x = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(x)) throw std::invalid_argument(item);
      q.push_back(x);
    } catch (const std::logic_error&) {
      throw UsageError(name + ": found '" + item + "'; expected a number");
    }
  }
  if (static_cast<int>(q.size()) != count)
    throw UsageError(name + ": found " + std::to_string(q.size()) + " values; expected " + std::to_string(count));
  return Eigen::Map<const Eigen::VectorXd>(q.data(), count);
}

std::unique_ptr<robot::ArmModel> arm_option(Args& args, const std::string& tip) {
  const std::string urdf = args.value("--urdf").value_or("robots/puma560.urdf");
  try {
    return std::make_unique<robot::ArmModel>(find_config_file(urdf), tip);
  } catch (const std::exception& e) {
    throw UsageError(std::string("--urdf: ") + e.what());
  }
}

void no_unknown_options(const Args& args) {
  const auto unknown = args.unknown_options();
  if (!unknown.empty()) throw UsageError("unknown option " + unknown.front());
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UsageError("cannot read '" + path + "'");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// wrist --readings FILE [--urdf U] [--sensor-frame F] [--scene S --out FILE] [limits]
int wrist(Args& args) {
  const std::string sensor_frame = args.value("--sensor-frame").value_or("ft_sensor");
  const auto readings_file = args.value("--readings");
  if (!readings_file) throw UsageError("--readings: expected the readings file (wysiwyf calibrate wrist-poses)");
  const auto scene = args.value("--scene"), out = args.value("--out");
  if (scene.has_value() != out.has_value()) throw UsageError("--scene and --out go together");
  robot::ToolLoadLimits limits;
  limits.min_poses = static_cast<int>(whole_option(args, "--min-poses", limits.min_poses, 3, 10000, "3 or more"));
  limits.max_condition =
      number_option(args, "--max-condition", limits.max_condition, 1, 1e6, "a condition number, 1 or more");
  limits.max_force_residual = number_option(args, "--max-force-residual", limits.max_force_residual, 0, 1000, "N");
  limits.max_torque_residual = number_option(args, "--max-torque-residual", limits.max_torque_residual, 0, 100, "N m");
  const auto arm = arm_option(args, sensor_frame);
  no_unknown_options(args);
  std::vector<robot::WristReading> readings;
  try {
    readings =
        robot::wrist_readings(*arm, arm->frame(sensor_frame), robot::load_wrist_readings(*readings_file, arm->dof()));
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
  const robot::ToolLoadFit fit = robot::fit_tool_load(readings, limits);
  std::cout << robot::describe(fit, limits);
  if (!fit.accepted) return 1;
  std::cout << "bias (arm_sim's ft_bias, or subtract it where the sensor is read): [" << fit.force_bias.x() << ", "
            << fit.force_bias.y() << ", " << fit.force_bias.z() << ", " << fit.torque_bias.x() << ", "
            << fit.torque_bias.y() << ", " << fit.torque_bias.z() << "]\n";
  if (scene) {
    std::string text;
    try {
      const std::string path = find_config_file(*scene);
      text = robot::with_tool_load(read_text(path), path, fit.tool_mass, fit.tool_com);
    } catch (const UsageError&) {
      throw;
    } catch (const std::exception& e) {
      throw UsageError(e.what());
    }
    std::ofstream o(*out);
    if (!(o << text)) throw UsageError("cannot write '" + *out + "'");
    std::cout << "wrote " << *out << " (the scene with device tool_mass and tool_com)\n";
  }
  return 0;
}

// wrist-poses --home Q [--urdf U] [--sensor-frame F] [--count N] [--out FILE]
int wrist_poses(Args& args) {
  const std::string sensor_frame = args.value("--sensor-frame").value_or("ft_sensor");
  const int count = static_cast<int>(whole_option(args, "--count", 12, 6, 200, "6 to 200 poses"));
  const auto out = args.value("--out");
  const auto arm = arm_option(args, sensor_frame);
  const Eigen::VectorXd home = joints_option(args, "--home", arm->dof());
  no_unknown_options(args);
  std::vector<robot::JointVector> poses;
  try {
    poses = robot::wrist_calibration_poses(*arm, home, arm->frame(sensor_frame), count);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--home: ") + e.what());
  }
  std::vector<robot::WristSample> samples;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    robot::WristSample s;
    s.label = "pose " + std::to_string(i + 1);
    s.joints = poses[i];
    samples.push_back(s);
  }
  const std::string text =
      "# The wrist calibration's poses: move the arm to each, let it settle, and replace the wrench\n"
      "# with the sensor's mean reading there (fx fy fz N, tx ty tz N m, bias included; nothing touching\n"
      "# the tool). Then: wysiwyf calibrate wrist --readings THIS_FILE\n" +
      robot::wrist_readings_yaml(samples);
  if (!out) {
    std::cout << text;
    return 0;
  }
  std::ofstream o(*out);
  if (!(o << text)) throw UsageError("cannot write '" + *out + "'");
  std::cout << "wrote " << poses.size() << " poses to " << *out << "\n";
  return 0;
}

}  // namespace

int cmd_calibrate(Args args) {
  const auto step = args.take_front();
  if (!step)
    throw UsageError(
        "expected a step: wrist-poses, wrist, board, intrinsics, stereo, camera-base-poses, camera-base, lamps");
  if (*step == "wrist") return wrist(args);
  if (*step == "wrist-poses") return wrist_poses(args);
  return calibrate_camera_step(*step, args);
}

}  // namespace wysiwyf::cli
