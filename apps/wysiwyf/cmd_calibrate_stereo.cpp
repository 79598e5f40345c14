// wysiwyf calibrate stereo: a stereo pair's extrinsics and rectification from images of the board
// seen by both cameras at once (each camera's intrinsics from `calibrate intrinsics`), checked by
// the epipolar error, written as the two calibration files the camera component reads.
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "calibrate_options.hpp"
#include "calibration/board_detection.hpp"
#include "calibration/camera_file.hpp"
#include "calibration/stereo_fit.hpp"

namespace wysiwyf::cli {

namespace cal = vision::calibration;

namespace {

cal::CameraFile camera_file(Args& args, const std::string& option) {
  const std::string path = required(args, option, "the camera's calibration file (wysiwyf calibrate intrinsics)");
  try {
    return cal::load_camera_file(path);
  } catch (const std::runtime_error& e) {
    throw UsageError(option + ": " + e.what());
  }
}

std::string report(const cal::StereoFit& fit, const std::vector<cal::BoardDetection>& left) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  for (std::size_t i = 0; i < left.size(); ++i) {
    out << "  " << left[i].name << ": ";
    if (fit.pair_epipolar[i] < 0)
      out << "left out (too few corners both cameras found)\n";
    else
      out << "epipolar " << fit.pair_epipolar[i] << " px RMS\n";
  }
  const Eigen::Vector3d t = fit.right_T_left.translation();
  out << "pairs used " << fit.pairs_used << " of " << left.size() << "; reprojection RMS " << fit.rms
      << " px; epipolar RMS " << fit.epipolar_rms << " px, max " << fit.epipolar_max << " px\n"
      << "right_T_left translation (m): " << t.x() << " " << t.y() << " " << t.z() << " (baseline " << t.norm() * 1e3
      << " mm), rotation " << Eigen::AngleAxisd(fit.right_T_left.linear()).angle() * 180 / 3.141592653589793
      << " deg\n";
  return out.str();
}

}  // namespace

// stereo --left FILE --right FILE --left-images DIR --right-images DIR --out-left FILE --out-right FILE
int calibrate_stereo(Args& args) {
  const cal::CharucoSpec spec = board_options(args);
  cal::CameraFile left = camera_file(args, "--left"), right = camera_file(args, "--right");
  const std::string left_dir = required(args, "--left-images", "a folder of the left camera's images of the board");
  const std::string right_dir = required(args, "--right-images", "a folder of the right camera's images of the board");
  const std::string out_left = required(args, "--out-left", "the left camera's file to write (yaml)");
  const std::string out_right = required(args, "--out-right", "the right camera's file to write (yaml)");
  cal::StereoLimits limits;
  limits.max_epipolar_rms = number_option(args, "--max-epipolar", limits.max_epipolar_rms, 0, 100, "px");
  no_unknown_options(args);
  if (left.intrinsics.size != right.intrinsics.size)
    throw UsageError("--left and --right: cameras of different image sizes; expected a pair of one model");
  // Pairs by file name: the same name in both folders is one board position.
  std::map<std::string, std::string> right_by_name;
  for (const std::string& f : image_files("--right-images", right_dir))
    right_by_name[std::filesystem::path(f).filename().string()] = f;
  const cal::CharucoTarget target(spec);
  std::vector<cal::BoardDetection> l, r;
  for (const std::string& f : image_files("--left-images", left_dir)) {
    const std::string name = std::filesystem::path(f).filename().string();
    const auto it = right_by_name.find(name);
    if (it == right_by_name.end()) {
      std::cout << "  " << name << ": no image of that name in " << right_dir << "; left out\n";
      continue;
    }
    for (const auto& [path, into] : {std::pair{f, &l}, std::pair{it->second, &r}}) {
      const cv::Mat image = read_grey(path);
      if (image.size() != left.intrinsics.size)
        throw UsageError(path + ": " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                         " px; expected the calibrated cameras' " + std::to_string(left.intrinsics.size.width) + "x" +
                         std::to_string(left.intrinsics.size.height));
      into->push_back(cal::detect_board(image, target, name));
    }
  }
  const cal::StereoFit fit = cal::fit_stereo(l, r, target, left.intrinsics, right.intrinsics, limits);
  std::cout << report(fit, l);
  if (!fit.accepted) {
    std::cout << "refused: " << fit.refusal << "\n";
    return 1;
  }
  left.rectification = fit.R1, left.projection = fit.P1;
  right.rectification = fit.R2, right.projection = fit.P2;
  const std::string comment = "wysiwyf calibrate stereo: " + std::to_string(fit.pairs_used) +
                              " board positions, epipolar RMS " + std::to_string(fit.epipolar_rms) + " px";
  cal::save_camera_file(out_left, left, comment + " (the left camera)");
  cal::save_camera_file(out_right, right, comment + " (the right camera)");
  std::cout << "wrote " << out_left << " and " << out_right << "\n";
  return 0;
}

}  // namespace wysiwyf::cli
